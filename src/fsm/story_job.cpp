#include "sims/fsm/story_job.h"

#include <cctype>
#include <fstream>
#include <utility>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/paths.h"
#include "sims/io/story_outputs.h"
#include "sims/language/embedding_bank.h"
#include "sims/planner/planner.h"
#include "sims/scene/loaders.h"
#include "sims/task/contact_plan.h"

namespace sims::fsm {

namespace {

std::vector<std::string> LowerWords(const std::string& text) {
  std::vector<std::string> out;
  std::string w;
  for (char c : text + " ") {
    if (std::isalpha(static_cast<unsigned char>(c))) {
      w += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else if (!w.empty()) {
      out.push_back(w);
      w.clear();
    }
  }
  return out;
}

bool IsPlanJson(const nlohmann::json& j) {
  return j.is_object() && j.contains("layout") && j.contains("keyframes") && j.contains("version");
}

}  // namespace

nlohmann::json InstructionToScriptJson(const std::string& sentence) {
  const auto& vocab = planner::Vocabulary::Default();
  const auto words = LowerWords(sentence);
  std::optional<planner::Skill> skill;
  std::string furniture = "floor";
  for (size_t i = 0; i < words.size(); ++i) {
    if (!skill) skill = vocab.FindSkill(words[i]);
    if (!skill && i + 1 < words.size()) skill = vocab.FindSkill(words[i] + " " + words[i + 1]);
    if (furniture == "floor") {
      if (i + 1 < words.size())
        if (auto f = vocab.FindFurniture(words[i] + " " + words[i + 1])) furniture = *f;
      if (furniture == "floor")
        if (auto f = vocab.FindFurniture(words[i])) furniture = *f;
    }
  }
  // Verbs the skill aliases may not list.
  for (const auto& w : words) {
    if (skill) break;
    if (w == "sits" || w == "seat" || w == "seated") skill = planner::Skill::kSit;
    if (w == "lies" || w == "lay" || w == "bed") skill = planner::Skill::kLie;
    if (w == "touch" || w == "touches" || w == "grab" || w == "pick")
      skill = planner::Skill::kReach;
    if (w == "walk" || w == "walks" || w == "go" || w == "goes" || w == "move")
      skill = planner::Skill::kWalk;
  }
  if (!skill)
    ThrowInputError("--instruction", "",
                    "a sentence naming an action (walk, sit, lie, reach/touch, get up)",
                    "'" + sentence + "'");
  nlohmann::json k = {
      {"skill", planner::SkillName(*skill)}, {"caption", sentence}, {"furniture", furniture}};
  return {{"keyframes", nlohmann::json::array({k})}};
}

nlohmann::json RunStoryJob(const StoryJob& job) {
  const int inputs =
      !job.input.empty() + !job.theme.empty() + !job.instruction.empty() + !job.scene_plan.empty();
  if (inputs != 1)
    ThrowInputError("run_story", "input",
                    "exactly one of: a script/plan file, --theme, --instruction, --scene-plan",
                    std::to_string(inputs) + " given");
  const std::filesystem::path policy_path =
      job.policies.empty() ? DefaultPolicySetPath() : std::filesystem::path(job.policies);
  const PolicySet policies = LoadPolicySet(policy_path);

  // ---- plan ------------------------------------------------------------------------------
  planner::PlannerConfig planner_config = planner::LoadPlannerConfig();
  planner_config.llm = planner::WithEnvironment(std::move(planner_config.llm), job.environment);
  planner::StoryPlanner planner(std::move(planner_config));
  planner::Plan plan;
  std::shared_ptr<scene::Scene> story_scene;
  std::vector<Instruction> instructions;
  nlohmann::json plan_json;  // what plan.json holds
  if (!job.scene_plan.empty()) {
    // UniHSI: the plan brings its own scene (PartNet objects) and chain of contacts.
    const auto loaded = task::LoadScenePlanRef(job.scene_plan, job.partnet_root);
    const task::ContactPlan& contacts = loaded.plan;
    story_scene = std::make_shared<scene::Scene>(*loaded.scene);
    instructions = BuildInstructions(contacts, *story_scene);
    plan.planner = "sceneplan";
    plan.theme = "UniHSI plan " + contacts.id;
    plan.layout.mode = "given";
    plan.narrative = "Chain of contacts " + contacts.id + " of " + loaded.file.filename().string() +
                     " (" + std::to_string(contacts.steps.size()) + " steps).";
    plan_json = {{"scene_plan", loaded.file.string()},
                 {"id", contacts.id},
                 {"plan", ReadJsonFile(loaded.file)[contacts.id]}};
  } else {
    if (!job.input.empty() && IsPlanJson(ReadJsonFile(job.input))) {
      plan = planner::LoadPlan(job.input);
      story_scene = std::make_shared<scene::Scene>(
          planner::MaterializeLayout(plan.layout, planner::DefaultSceneLoader()));
    } else {
      story_scene = std::make_shared<scene::Scene>(scene::LoadSceneFile(job.scene));
      planner::ScriptResult script;
      if (!job.input.empty()) {
        script = planner.ScriptFromFile(job.input);
      } else if (!job.theme.empty()) {
        const planner::Difficulty d = planner::ParseDifficulty(job.difficulty);
        script = planner.ScriptForTheme(job.theme, d, job.options.seed);
      } else {
        script.script =
            planner::LongScriptFromJson(InstructionToScriptJson(job.instruction), "--instruction");
        script.planner = "instruction";
      }
      plan = planner.Place(script, *story_scene);
    }
    if (plan.keyframes.empty())
      ThrowInputError(job.input.empty() ? "story" : job.input, "keyframes", "at least one keyframe",
                      "none");
    ValidateConfig(plan, "plan");
    plan_json = planner::PlanToJson(plan);
    const scene::RayCaster caster(*story_scene);
    instructions = BuildInstructions(plan, *story_scene, caster);
  }

  // ---- run -------------------------------------------------------------------------------
  StoryRunner runner(story_scene, policies, job.options);
  if (job.goal) {
    // LINGO's optional goal location: the interaction (or final walk) aims at it.
    for (auto it = instructions.rbegin(); it != instructions.rend(); ++it) {
      it->target.point = *job.goal;
      it->target.has_point = true;
      break;
    }
  }
  // Caption → z through the motion–text model, and what the caption was understood as.
  nlohmann::json styles = nlohmann::json::array();
  const std::filesystem::path style_model = job.style_model.empty()
                                                ? DataPath("language/text_motion")
                                                : std::filesystem::path(job.style_model);
  if (std::filesystem::exists(style_model / "bank.json") || !job.style_model.empty()) {
    const auto embedder = language::StyleEmbedder::Load(style_model);
    for (auto& in : instructions) {
      const auto q = embedder.Lookup(in.caption.empty() ? in.skill : in.caption, 3);
      in.z = q.z;
      auto j = language::StyleQueryToJson(q);
      j.erase("z");
      styles.push_back(j);
    }
  }
  runner.CheckPolicies(instructions);
  const Eigen::Vector3d start = runner.DefaultStart(instructions);
  io::MotionRecordBuilder recorder(runner.humanoid());
  recorder.SetTitle(plan.theme.empty() ? (job.instruction.empty() ? job.input : job.instruction)
                                       : plan.theme);
  recorder.SetScene({story_scene->name, plan.layout.mode == "given" ? job.scene : ""});
  const StoryResult result = runner.Run(instructions, start, 0.0, &recorder);
  const io::MotionRecord record = recorder.Finish();

  // ---- outputs ---------------------------------------------------------------------------
  const std::filesystem::path out = job.out_dir;
  std::filesystem::path partial = out;
  partial += ".partial";
  std::filesystem::remove_all(partial);
  std::filesystem::create_directories(partial);
  nlohmann::json result_json = StoryResultToJson(result);
  result_json["planner"] = plan.planner;
  result_json["planner_note"] = plan.planner_note;
  result_json["scene"] = story_scene->name;
  result_json["seed"] = job.options.seed;
  result_json["policies"] = policy_path.string();
  result_json["styles"] = styles;
  io::StoryOutputOptions out_opt;
  out_opt.video = job.video;
  out_opt.geometry = &runner.geometry();
  io::WriteStoryOutputs(partial, record, *story_scene, out_opt);
  WriteJsonFile(partial / "plan.json", plan_json);
  std::string story = plan.narrative + "\n\n";
  for (const auto& k : result.keyframes)
    story += "- [" + std::string(k.success ? "ok" : "failed") + "] " + k.skill + ": " + k.caption +
             (k.object.empty() ? "" : " (" + k.object + ")") +
             (k.note.empty() ? "" : " — " + k.note) + "\n";
  WriteFileAtomic(partial / "story.txt", story);
  WriteJsonFile(partial / "config.json",
                {{"input", job.input},
                 {"theme", job.theme},
                 {"scene_plan", job.scene_plan},
                 {"instruction", job.instruction},
                 {"difficulty", job.difficulty},
                 {"scene", job.scene},
                 {"policies", policy_path.string()},
                 {"video", job.video},
                 {"options", ConfigToJson(job.options)},
                 {"goal", job.goal ? nlohmann::json({job.goal->x(), job.goal->y(), job.goal->z()})
                                   : nlohmann::json()}});
  WriteJsonFile(partial / "result.json", result_json);  // last: its presence marks completion
  std::filesystem::remove_all(out);
  std::filesystem::rename(partial, out);
  spdlog::info("story: {}/{} keyframes succeeded, {} falls, {:.1f} s simulated; outputs in {}",
               static_cast<int>(result.success_rate * result.keyframes.size() + 0.5),
               result.keyframes.size(), result.falls, result.duration_s, out.string());
  return result_json;
}

}  // namespace sims::fsm
