#include "sims/planner/planner.h"

#include <fstream>
#include <sstream>
#include <utility>

#include <spdlog/spdlog.h>

#include "sims/core/paths.h"
#include "sims/planner/prompt.h"
#include "sims/planner/text.h"

namespace sims::planner {

using nlohmann::json;

PlannerConfig LoadPlannerConfig(const std::filesystem::path& path) {
  return LoadConfig<PlannerConfig>(path.empty() ? ConfigPath("planner/planner.json") : path);
}

StoryPlanner::StoryPlanner(PlannerConfig config, TextEmbedder embedder)
    : config_(std::move(config)) {
  ValidateConfig(config_, "planner config");
  vocab_ = std::make_unique<Vocabulary>(Vocabulary::Load(config_.vocabulary));
  lexicon_ = std::make_unique<EmotionLexicon>(EmotionLexicon::Load(config_.emotion_lexicon));
  std::vector<std::filesystem::path> extras(config_.extra_scripts.begin(),
                                            config_.extra_scripts.end());
  db_ = std::make_unique<ScriptDatabase>(
      ScriptDatabase::LoadWithExtras(config_.scripts_dir, extras, *vocab_));
  embedded_ = std::make_unique<ThemePlanner>(*db_, *vocab_, *lexicon_, config_.retrieval,
                                             config_.difficulty, std::move(embedder));
}

StoryPlanner::~StoryPlanner() = default;

ScriptResult StoryPlanner::EmbeddedScript(const std::string& theme, Difficulty difficulty,
                                          uint64_t seed) const {
  ScriptResult r;
  r.script = embedded_->Plan(theme, difficulty, seed);
  r.planner = "embedded";
  return r;
}

ScriptResult StoryPlanner::ScriptForTheme(const std::string& theme, Difficulty difficulty,
                                          uint64_t seed) const {
  if (config_.llm.endpoint.empty()) {
    ScriptResult r = EmbeddedScript(theme, difficulty, seed);
    r.note =
        "no LLM endpoint configured (--llm-endpoint or $SIMS_LLM_ENDPOINT): used the "
        "embedded planner";
    return r;
  }
  try {
    return LlmScript(theme, difficulty, seed);
  } catch (const Error& e) {
    ScriptResult r = EmbeddedScript(theme, difficulty, seed);
    r.note =
        std::string("LLM back-end failed (") + e.what() + "): fell back to the embedded planner";
    spdlog::warn("{}", r.note);
    return r;
  }
}

std::pair<std::string, std::string> StoryPlanner::LlmPrompts(const std::string& theme,
                                                             Difficulty difficulty) const {
  std::array<int, 2> range = config_.difficulty.Range(difficulty);
  std::string candidates;
  for (int idx : embedded_->Candidates(theme, config_.llm.candidates)) {
    const ShortScript& s = db_->scripts()[idx];
    json line = {{"id", s.id}, {"emotion", s.emotion}, {"scene", s.scene}, {"summary", s.summary}};
    json kfs = json::array();
    for (const Keyframe& k : s.keyframes)
      kfs.push_back({SkillName(k.skill), k.caption, k.furniture});
    line["keyframes"] = kfs;
    candidates += line.dump() + "\n";
  }
  std::map<std::string, std::string> values = VocabularyPromptValues(*vocab_);
  values["theme"] = theme;
  values["difficulty"] = DifficultyName(difficulty);
  values["min_interactions"] = std::to_string(range[0]);
  values["max_interactions"] = std::to_string(range[1]);
  values["candidates"] = candidates;
  return {FillPrompt(ReadPromptTemplate(config_.llm.system_prompt), values),
          FillPrompt(ReadPromptTemplate(config_.llm.user_prompt), values)};
}

LongScript StoryPlanner::ParseLlmReply(const std::string& content, Difficulty difficulty) const {
  const std::string source = "LLM reply";
  std::string text = StripToJson(content);
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception&) {  // parse_error, or out_of_range for a huge number
    (void)ParseShortScriptText(text, source, GrammarMode::kLenient, *vocab_);  // clear message
    throw;
  }
  if (!j.is_object())
    ThrowInputError(source, "", "a JSON object {\"scripts\": [...], \"narrative\": \"...\"}",
                    text.substr(0, 60));
  std::vector<ShortScript> scripts;
  if (j.contains("scripts")) {
    const json& arr = j["scripts"];
    if (!arr.is_array() || arr.empty())
      ThrowInputError(source, "scripts", "a non-empty list of script ids or short scripts",
                      arr.dump().substr(0, 60));
    for (std::size_t i = 0; i < arr.size(); ++i) {
      std::string field = "scripts[" + std::to_string(i) + "]";
      if (arr[i].is_string()) {
        const ShortScript* s = db_->Find(arr[i].get<std::string>());
        if (!s)
          ThrowInputError(source, field, "the id of a candidate short script",
                          "'" + arr[i].get<std::string>() + "'");
        scripts.push_back(*s);
      } else {
        ShortScript s =
            ParseShortScript(arr[i], source + " " + field, GrammarMode::kLenient, *vocab_);
        if (s.id.empty()) s.id = "llm_" + std::to_string(i);
        scripts.push_back(std::move(s));
      }
    }
  } else if (j.contains("keyframes")) {
    ShortScript s = ParseShortScript(j, source, GrammarMode::kLenient, *vocab_);
    s.id = "llm_0";
    scripts.push_back(std::move(s));
  } else {
    ThrowInputError(source, "scripts", "a list of script ids or short scripts", "nothing");
  }
  LongScript ls = ConcatenateScripts(scripts, source, *vocab_);
  std::array<int, 2> range = config_.difficulty.Range(difficulty);
  int n = ls.Interactions();
  if (n < range[0])
    ThrowInputError(source, "scripts",
                    "between " + std::to_string(range[0]) + " and " + std::to_string(range[1]) +
                        " interactions for a " + DifficultyName(difficulty) + " story",
                    std::to_string(n));
  if (n > range[1]) {
    // Too long: keep the first max interactions (and a get-up right after the last one).
    std::vector<Keyframe> kept;
    int got = 0;
    for (const Keyframe& k : ls.keyframes) {
      if (got == range[1] && k.skill != Skill::kGetUp) break;
      kept.push_back(k);
      if (IsInteraction(k.skill)) ++got;
      if (got == range[1] && k.skill == Skill::kGetUp) break;
    }
    ls.keyframes = kept;
  }
  if (auto it = j.find("narrative"); it != j.end()) {
    if (!it->is_string())
      ThrowInputError(source, "narrative", "a string", it->dump().substr(0, 60));
    ls.narrative = Trim(it->get<std::string>());
  }
  return ls;
}

ScriptResult StoryPlanner::LlmScript(const std::string& theme, Difficulty difficulty,
                                     uint64_t seed) const {
  auto [system, user] = LlmPrompts(theme, difficulty);
  std::string content =
      ChatCompletion(config_.llm, {{"system", system, {}}, {"user", user, {}}}, seed);
  ScriptResult r;
  r.script = ParseLlmReply(content, difficulty);
  r.script.theme = theme;
  r.script.difficulty = difficulty;
  r.script.seed = seed;
  r.script.arc = lexicon_->Arc(theme);
  if (r.script.narrative.empty()) r.script.narrative = TemplateNarrative(r.script, {}, *vocab_);
  r.planner = "llm:" + config_.llm.model;
  return r;
}

ScriptResult StoryPlanner::ScriptFromFile(const std::filesystem::path& path) const {
  ScriptResult r;
  r.script = LoadLongScript(path, *vocab_);
  r.planner = "script";
  return r;
}

Plan StoryPlanner::Place(const ScriptResult& script, const LayoutDatabase& layouts) const {
  return BuildPlan(script, MatchLayouts(script.script, layouts, config_.layout, *vocab_), *vocab_);
}

Plan StoryPlanner::Place(const ScriptResult& script, const scene::Scene& scene) const {
  return BuildPlan(script, MatchScene(script.script, scene, config_.layout, *vocab_), *vocab_);
}

Plan StoryPlanner::PlaceInSceneFile(const ScriptResult& script,
                                    const std::string& scene_path) const {
  LayoutSource src;
  src.kind = "scene_file";
  src.path = scene_path;
  src.name = scene_path;
  scene::Scene scene = DefaultSceneLoader()(src);
  Plan p = Place(script, scene);
  // Record how to rebuild the scene: one "single" room whose source is the file.
  PlanRoom room;
  room.id = scene.name.empty() ? "scene" : scene.name;
  room.type = scene.rooms.size() == 1 ? p.layout.rooms.front().type : "house";
  room.source = src;
  p.layout.mode = "single";
  p.layout.rooms = {room};
  return p;
}

Plan BuildPlan(const ScriptResult& sr, const LayoutMatch& match, const Vocabulary& vocab) {
  const LongScript& ls = sr.script;
  SIMS_CHECK(match.bindings.size() == ls.keyframes.size());
  Plan p;
  p.theme = ls.theme;
  p.difficulty = DifficultyName(ls.difficulty);
  p.seed = ls.seed;
  p.planner = sr.planner;
  p.planner_note = sr.note;
  for (const ArcSegment& a : ls.arc)
    if (p.arc.empty() || p.arc.back() != a.emotion) p.arc.push_back(a.emotion);
  if (p.arc.empty()) p.arc = ls.EmotionSequence();
  p.script_ids = ls.script_ids;
  std::vector<std::string> bound_names(ls.keyframes.size());
  for (std::size_t i = 0; i < ls.keyframes.size(); ++i) {
    const Keyframe& k = ls.keyframes[i];
    const Binding& b = match.bindings[i];
    PlanKeyframe pk;
    pk.index = static_cast<int>(i);
    pk.skill = SkillName(k.skill);
    pk.caption = k.caption;
    pk.emotion = k.emotion;
    pk.style = k.style;
    pk.furniture = k.furniture;
    pk.instance = k.instance;
    pk.object = b.object;
    pk.object_category = b.object_category;
    pk.room = b.room;
    pk.script_id = k.script_id;
    pk.segment = k.segment;
    pk.inserted = k.inserted;
    pk.placed = b.placed;
    pk.note = b.note;
    if (k.furniture != "floor" && b.placed) bound_names[i] = b.object_category;
    p.keyframes.push_back(pk);
  }
  p.layout = match.layout;
  // The LLM's (or the script file's) own story is kept; the embedded planner's template is
  // rewritten so it names the furniture actually used.
  p.narrative = sr.planner == "embedded" || ls.narrative.empty()
                    ? TemplateNarrative(ls, bound_names, vocab)
                    : ls.narrative;
  p.warnings = match.warnings;
  return p;
}

LayoutDatabase BuiltinLayoutDatabase(const LayoutConfig& config) {
  std::vector<std::string> log;
  LayoutDatabase db = BuildLayoutDatabase(true, false, {}, {}, config, &log);
  for (const std::string& l : log) spdlog::debug("{}", l);
  return db;
}

Plan PlanStory(const PlanRequest& req, TextEmbedder embedder) {
  if (req.theme.empty() == req.script.empty())
    ThrowInputError("plan_story", "--theme / --script", "exactly one of them",
                    req.theme.empty() ? "neither" : "both");
  PlannerConfig config = LoadPlannerConfig(req.config);
  if (!req.llm_endpoint.empty()) config.llm.endpoint = req.llm_endpoint;
  if (!req.llm_model.empty()) config.llm.model = req.llm_model;
  if (!req.llm_key.empty()) config.llm.api_key = req.llm_key;
  if (req.llm_timeout_s > 0) config.llm.timeout_s = req.llm_timeout_s;
  config.llm = WithEnvironment(std::move(config.llm), req.environment);
  config.extra_scripts.insert(config.extra_scripts.end(), req.extra_scripts.begin(),
                              req.extra_scripts.end());
  StoryPlanner planner(config, std::move(embedder));
  ScriptResult script =
      req.script.empty()
          ? planner.ScriptForTheme(req.theme, ParseDifficulty(req.difficulty), req.seed)
          : planner.ScriptFromFile(req.script);
  if (!req.scene.empty()) return planner.PlaceInSceneFile(script, req.scene);
  LayoutDatabase layouts = req.layouts.empty() ? BuiltinLayoutDatabase(config.layout)
                                               : LayoutDatabase::Load(req.layouts);
  return planner.Place(script, layouts);
}

}  // namespace sims::planner
