#include "sims/planner/imitation.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>

#include <spdlog/spdlog.h>

#include "sims/core/error.h"
#include "sims/core/rng.h"
#include "sims/planner/llm_client.h"
#include "sims/planner/prompt.h"
#include "sims/planner/text.h"

namespace sims::planner {

using nlohmann::json;

void ImitationOptions::Validate() const {
  if (count < 1 || count > 10000)
    ThrowInputError("imitate_scripts", "--count", "1 to 10000 scripts", std::to_string(count));
  if (examples < 1) ThrowInputError("imitate_scripts", "examples", "at least 1");
  if (max_attempts < 0) ThrowInputError("imitate_scripts", "max_attempts", "0 (auto) or more");
  if (!(timeout_s > 0))
    ThrowInputError("imitate_scripts", "timeout", "a positive number of seconds");
  if (max_tokens <= 0) ThrowInputError("imitate_scripts", "max_tokens", "a positive integer");
  if (temperature < 0) ThrowInputError("imitate_scripts", "temperature", "a non-negative number");
  if (id_prefix.empty() || id_prefix.find_first_of("/\\ ") != std::string::npos)
    ThrowInputError("imitate_scripts", "id_prefix", "a non-empty name without slashes or spaces",
                    "'" + id_prefix + "'");
}

namespace {

// An interaction with the walk that leads to it and the get-up that ends it: the piece of a
// script that still makes sense next to pieces of other scripts.
struct Unit {
  std::vector<Keyframe> keyframes;
  std::string source;
};

std::vector<Unit> SplitUnits(const ShortScript& s) {
  std::vector<Unit> units;
  const Keyframe* walk = nullptr;
  for (const Keyframe& k : s.keyframes) {
    if (k.skill == Skill::kWalk) {
      walk = &k;
    } else if (IsInteraction(k.skill)) {
      Unit u;
      u.source = s.id;
      if (walk && (walk->furniture == k.furniture || walk->furniture == "floor"))
        u.keyframes.push_back(*walk);
      u.keyframes.push_back(k);
      units.push_back(std::move(u));
      walk = nullptr;
    } else if (!units.empty()) {  // get-up closes the unit it follows
      units.back().keyframes.push_back(k);
    }
  }
  return units;
}

template <class T>
void Shuffle(std::vector<T>* v, Rng* rng) {
  for (std::size_t i = v->size(); i > 1; --i)
    std::swap((*v)[i - 1], (*v)[static_cast<std::size_t>(rng->UniformInt(i))]);
}

std::string SummaryFor(const std::vector<Keyframe>& kfs, const std::string& emotion,
                       const std::string& scene, const Vocabulary& vocab) {
  const EmotionSpec* e = vocab.EmotionByName(emotion);
  std::string adjective = e && !e->adjective.empty() ? e->adjective : emotion;
  std::vector<std::string> parts;
  for (const Keyframe& k : kfs)
    if (IsInteraction(k.skill) && !k.caption.empty()) parts.push_back(k.caption);
  std::string article = std::string("aeiou").find(adjective[0]) != std::string::npos ? "An " : "A ";
  return article + adjective + " person in the " + scene + " " + Join(parts, ", then ") + ".";
}

// Same-emotion recombination of two scripts' units; nullopt when the pieces do not fit.
std::optional<ShortScript> Recombine(const std::vector<const ShortScript*>& pool, Rng* rng,
                                     const Vocabulary& vocab, std::vector<std::string>* sources) {
  const ShortScript& base = *pool[static_cast<std::size_t>(rng->UniformInt(pool.size()))];
  std::vector<const ShortScript*> same_room, others;
  for (const ShortScript* s : pool) {
    if (s == &base) continue;
    (s->scene == base.scene ? same_room : others).push_back(s);
  }
  const std::vector<const ShortScript*>& partners = same_room.empty() ? others : same_room;
  std::vector<Unit> mine = SplitUnits(base), theirs;
  const ShortScript* partner = nullptr;
  if (!partners.empty()) {
    partner = partners[static_cast<std::size_t>(rng->UniformInt(partners.size()))];
    theirs = SplitUnits(*partner);
  }
  if (mine.empty()) return std::nullopt;
  Shuffle(&mine, rng);
  Shuffle(&theirs, rng);
  // One unit of each script, sometimes a third one, in a random order.
  std::vector<Unit> chosen = {mine[0]};
  if (!theirs.empty()) chosen.push_back(theirs[0]);
  std::vector<Unit> rest(mine.begin() + 1, mine.end());
  if (theirs.size() > 1) rest.insert(rest.end(), theirs.begin() + 1, theirs.end());
  if (!rest.empty() && (chosen.size() < 2 || rng->Bernoulli(0.5)))
    chosen.push_back(rest[static_cast<std::size_t>(rng->UniformInt(rest.size()))]);
  Shuffle(&chosen, rng);
  while (!chosen.empty()) {
    ShortScript s;
    s.emotion = base.emotion;
    s.scene = base.scene;
    s.source = "template imitation";
    std::vector<Keyframe> kfs;
    for (const Unit& u : chosen)
      for (Keyframe k : u.keyframes) {
        // A unit's walk to the object the character already stands at (after a reach) would
        // be a walk on the spot.
        if (k.skill == Skill::kWalk && !kfs.empty() && kfs.back().skill == Skill::kReach &&
            kfs.back().furniture == k.furniture && kfs.back().instance == k.instance)
          continue;
        k.inserted = false;
        kfs.push_back(k);
      }
    try {
      s.keyframes = InsertTransitions(kfs, s.source, vocab);
    } catch (const Error&) {
      return std::nullopt;
    }
    if (static_cast<int>(s.keyframes.size()) <= kMaxShortScriptKeyframes) {
      s.summary = SummaryFor(s.keyframes, s.emotion, s.scene, vocab);
      sources->clear();
      for (const Unit& u : chosen)
        if (std::find(sources->begin(), sources->end(), u.source) == sources->end())
          sources->push_back(u.source);
      return s;
    }
    chosen.pop_back();  // too long for a short script: drop a unit
  }
  return std::nullopt;
}

json ExampleLine(const ShortScript& s) {
  json kfs = json::array();
  for (const Keyframe& k : s.keyframes) {
    std::vector<std::string> tags = k.tags.empty() ? std::vector<std::string>{k.emotion} : k.tags;
    kfs.push_back({{"skill", SkillName(k.skill)},
                   {"emotion/style", Join(tags, ", ")},
                   {"caption", k.caption},
                   {"furniture", k.furniture}});
  }
  return {{"summary", s.summary}, {"emotion", s.emotion}, {"scene", s.scene}, {"keyframes", kfs}};
}

}  // namespace

ImitationResult ImitateScripts(const ScriptDatabase& db, const ImitationOptions& options,
                               const Vocabulary& vocab) {
  options.Validate();
  if (db.size() == 0) ThrowInputError("imitate_scripts", "--db", "a non-empty database", "none");
  std::map<std::string, std::vector<const ShortScript*>> by_emotion;
  for (const ShortScript& s : db.scripts()) by_emotion[s.emotion].push_back(&s);
  std::vector<std::string> emotions;
  for (const auto& [e, scripts] : by_emotion) emotions.push_back(e);
  std::set<std::string> seen;
  for (const ShortScript& s : db.scripts()) seen.insert(KeyframeSignature(s.keyframes));

  const bool online = !options.endpoint.empty();
  const int max_attempts = options.max_attempts > 0 ? options.max_attempts : 4 * options.count;
  Rng rng(options.seed);
  const std::size_t start = static_cast<std::size_t>(rng.UniformInt(emotions.size()));
  std::string system_prompt, user_template;
  if (online) {
    std::map<std::string, std::string> values = VocabularyPromptValues(vocab);
    system_prompt = FillPrompt(ReadPromptTemplate(options.system_prompt), values);
    user_template = FillPrompt(ReadPromptTemplate(options.user_prompt), values);
  }
  LlmConfig llm;
  llm.model = options.model;
  llm.temperature = options.temperature;
  llm.max_tokens = options.max_tokens;

  ImitationResult result;
  while (static_cast<int>(result.scripts.size()) < options.count &&
         result.attempts < max_attempts) {
    const int attempt = result.attempts++;
    // Emotions take turns so that a run covers the database's moods evenly.
    const std::string& emotion = emotions[(start + attempt) % emotions.size()];
    const std::vector<const ShortScript*>& pool = by_emotion[emotion];
    std::vector<std::string> sources, notes;
    ShortScript script;
    if (online) {
      std::vector<const ShortScript*> examples = pool;
      Shuffle(&examples, &rng);
      if (static_cast<int>(examples.size()) > options.examples) examples.resize(options.examples);
      std::string lines;
      for (const ShortScript* s : examples) {
        lines += ExampleLine(*s).dump() + "\n";
        sources.push_back(s->id);
      }
      std::string user = FillPrompt(
          user_template,
          {{"examples", lines}, {"emotion", emotion}, {"scene", examples.front()->scene}});
      const uint64_t request_seed = options.seed * 1000003ULL + static_cast<uint64_t>(attempt);
      std::string content;
      try {
        content = PostChatRequest(
            options.endpoint, options.api_key,
            ChatRequestJson(llm, {{"system", system_prompt, {}}, {"user", user, {}}}, request_seed),
            options.timeout_s);
      } catch (const LlmError& e) {
        // Bad replies are dropped like invalid scripts; an endpoint that cannot be reached or
        // refuses (time-out, HTTP error) would fail every request, so the run stops.
        if (e.kind() == LlmError::Kind::kProtocol || e.kind() == LlmError::Kind::kReply) {
          result.dropped.push_back("request " + std::to_string(attempt) + ": " + e.what());
          continue;
        }
        throw LlmError(e.kind(), "LLM endpoint " + options.endpoint + ": " + e.what());
      }
      try {
        script = ParseScriptAnswer(
            content,
            "LLM answer from " + options.endpoint + " (request " + std::to_string(attempt) + ")",
            options.unknown, &notes, vocab);
      } catch (const Error& e) {
        result.dropped.push_back(e.what());
        continue;
      }
    } else {
      std::optional<ShortScript> s = Recombine(pool, &rng, vocab, &sources);
      if (!s) {
        result.dropped.push_back("recombination " + std::to_string(attempt) + " (" + emotion +
                                 "): the pieces do not form a short script");
        continue;
      }
      // Through the same validator as model answers, so both paths write the same kind of file.
      script = ValidateScriptAnswer(ShortScriptToJson(*s), "template imitation",
                                    UnknownTerms::kReject, &notes, vocab);
    }
    std::string signature = KeyframeSignature(script.keyframes);
    if (!seen.insert(signature).second) {
      result.dropped.push_back((online ? "request " : "recombination ") + std::to_string(attempt) +
                               ": duplicate keyframe sequence (already in the database or this "
                               "run): " +
                               signature);
      continue;
    }
    char id[64];
    std::snprintf(id, sizeof(id), "_s%llu_%03zu", static_cast<unsigned long long>(options.seed),
                  result.scripts.size());
    script.id = options.id_prefix + id;
    script.source = script.id;
    for (Keyframe& k : script.keyframes) k.script_id = script.id;
    ImitatedScript out;
    out.script = std::move(script);
    out.provenance = {
        {"method", online ? "llm" : "template"}, {"seed", options.seed}, {"attempt", attempt},
        {"requested_emotion", emotion},          {"sources", sources},   {"notes", notes}};
    if (online) {
      out.provenance["model"] = options.model;
      out.provenance["endpoint"] = options.endpoint;
    }
    result.scripts.push_back(std::move(out));
  }
  for (const std::string& d : result.dropped) spdlog::debug("imitate_scripts: dropped {}", d);
  return result;
}

std::vector<std::filesystem::path> WriteImitatedScripts(const ImitationResult& result,
                                                        const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  std::vector<std::filesystem::path> paths;
  for (const ImitatedScript& s : result.scripts) {
    std::filesystem::path p = dir / (s.script.id + ".json");
    WriteShortScript(p, s.script, s.provenance);
    paths.push_back(p);
  }
  return paths;
}

}  // namespace sims::planner
