#include "sims/story/story.h"

#include <utility>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/paths.h"
#include "sims/io/story_outputs.h"
#include "sims/language/embedding_bank.h"
#include "sims/planner/planner.h"
#include "sims/planner/sentence.h"
#include "sims/scene/loaders.h"
#include "sims/scene/ray_caster.h"
#include "sims/task/contact_plan.h"

namespace sims::story {

namespace {

bool IsPlanJson(const nlohmann::json& j) {
  return j.is_object() && j.contains("layout") && j.contains("keyframes") && j.contains("version");
}

// UniHSI: the plan brings its own scene (PartNet objects) and chain of contacts.
void PrepareScenePlan(const StoryInput& input, PreparedStory* p) {
  const auto loaded = task::LoadScenePlanRef(input.scene_plan, input.partnet_root);
  const task::ContactPlan& contacts = loaded.plan;
  auto scene = std::make_shared<const scene::Scene>(*loaded.scene);
  p->instructions = fsm::BuildInstructions(contacts, *scene);
  p->scene = std::move(scene);
  p->plan.planner = "sceneplan";
  p->plan.theme = "UniHSI plan " + contacts.id;
  p->plan.layout.mode = "given";
  p->plan.narrative = "Chain of contacts " + contacts.id + " of " +
                      loaded.file.filename().string() + " (" +
                      std::to_string(contacts.steps.size()) + " steps).";
  p->plan_json = {{"scene_plan", loaded.file.string()},
                  {"id", contacts.id},
                  {"plan", ReadJsonFile(loaded.file)[contacts.id]}};
}

// Script, plan file, theme or sentence → plan bound to a scene → instructions.
void PreparePlan(const StoryInput& input, PreparedStory* p) {
  planner::PlannerConfig planner_config = planner::LoadPlannerConfig();
  planner_config.llm = planner::WithEnvironment(std::move(planner_config.llm), input.environment);
  const planner::LayoutConfig layout_config = planner_config.layout;
  planner::StoryPlanner planner(std::move(planner_config));
  std::shared_ptr<const scene::Scene> scene;
  if (!input.input.empty() && IsPlanJson(ReadJsonFile(input.input))) {
    p->plan = planner::LoadPlan(input.input);
    scene = std::make_shared<const scene::Scene>(
        planner::MaterializeLayout(p->plan.layout, planner::DefaultSceneLoader()));
  } else {
    planner::ScriptResult script;
    if (!input.input.empty()) {
      script = planner.ScriptFromFile(input.input);
    } else if (!input.theme.empty()) {
      script = planner.ScriptForTheme(input.theme, planner::ParseDifficulty(input.difficulty),
                                      input.seed);
    } else {
      script = {planner::LongScriptFromJson(planner::InstructionToScriptJson(input.instruction),
                                            "--instruction"),
                "instruction", ""};
    }
    if (input.scene.empty()) {
      // No scene given: choose a built-in layout that fits the script (plan_story's default).
      p->plan = planner.Place(script, planner::BuiltinLayoutDatabase(layout_config));
      scene = std::make_shared<const scene::Scene>(
          planner::MaterializeLayout(p->plan.layout, planner::DefaultSceneLoader()));
    } else {
      scene = std::make_shared<const scene::Scene>(scene::LoadSceneFile(input.scene));
      p->plan = planner.Place(script, *scene);
    }
  }
  if (p->plan.keyframes.empty())
    ThrowInputError(input.input.empty() ? "story" : input.input, "keyframes",
                    "at least one keyframe", "none");
  ValidateConfig(p->plan, "plan");
  p->plan_json = planner::PlanToJson(p->plan);
  const scene::RayCaster caster(*scene);
  p->instructions = fsm::BuildInstructions(p->plan, *scene, caster);
  p->scene = std::move(scene);
}

// Caption → z through the motion–text model, and what each caption was understood as.
void AddStyles(const StoryInput& input, PreparedStory* p) {
  const std::filesystem::path model = input.style_model.empty()
                                          ? DataPath("language/text_motion")
                                          : std::filesystem::path(input.style_model);
  if (!std::filesystem::exists(model / "bank.json") && input.style_model.empty()) return;
  const auto embedder = language::StyleEmbedder::Load(model);
  for (auto& in : p->instructions) {
    const auto q = embedder.Lookup(in.caption.empty() ? in.skill : in.caption, 3);
    in.z = q.z;
    auto j = language::StyleQueryToJson(q);
    j.erase("z");
    p->styles.push_back(j);
  }
}

}  // namespace

PreparedStory PrepareStory(const StoryInput& input) {
  const int inputs = !input.input.empty() + !input.theme.empty() + !input.instruction.empty() +
                     !input.scene_plan.empty();
  if (inputs != 1)
    ThrowInputError("run_story", "input",
                    "exactly one of: a script/plan file, --theme, --instruction, --scene-plan",
                    std::to_string(inputs) + " given");
  PreparedStory p;
  p.input = input;
  if (!input.scene_plan.empty())
    PrepareScenePlan(input, &p);
  else
    PreparePlan(input, &p);
  if (input.goal) {
    // LINGO's optional goal location: the interaction (or final walk) aims at it.
    if (!p.instructions.empty()) {
      p.instructions.back().target.point = *input.goal;
      p.instructions.back().target.has_point = true;
    }
  }
  AddStyles(input, &p);
  p.title = p.plan.theme.empty() ? (input.instruction.empty() ? input.input : input.instruction)
                                 : p.plan.theme;
  return p;
}

StoryRun RunStory(const PreparedStory& story, const fsm::PolicySet& policies,
                  const fsm::StoryOptions& options) {
  fsm::StoryRunner runner(story.scene, policies, options);
  runner.CheckPolicies(story.instructions);
  const Eigen::Vector3d start = runner.DefaultStart(story.instructions);
  io::MotionRecordBuilder recorder(runner.humanoid());
  recorder.SetTitle(story.title);
  recorder.SetScene(
      {story.scene->name, story.plan.layout.mode == "given" ? story.input.scene : ""});
  StoryRun run;
  run.result = runner.Run(story.instructions, start, 0.0, &recorder);
  run.record = recorder.Finish();
  run.story = story;
  run.policies = policies.source;
  run.options = options;
  run.geometry = std::make_shared<const sim::StaticGeometry>(runner.geometry());
  run.humanoid = runner.humanoid();
  return run;
}

nlohmann::json StoryRunToJson(const StoryRun& run) {
  nlohmann::json j = fsm::StoryResultToJson(run.result);
  j["planner"] = run.story.plan.planner;
  j["planner_note"] = run.story.plan.planner_note;
  j["scene"] = run.story.scene->name;
  j["seed"] = run.options.seed;
  j["policies"] = run.policies.string();
  j["styles"] = run.story.styles;
  return j;
}

nlohmann::json WriteStoryRun(const std::filesystem::path& dir, const StoryRun& run,
                             const StoryWriteOptions& options) {
  std::filesystem::path partial = dir;
  partial += ".partial";
  std::filesystem::remove_all(partial);
  std::filesystem::create_directories(partial);
  const nlohmann::json result_json = StoryRunToJson(run);
  io::StoryOutputOptions out_opt;
  out_opt.video = options.video;
  out_opt.geometry = run.geometry.get();
  io::WriteStoryOutputs(partial, run.record, *run.story.scene, out_opt);
  WriteJsonFile(partial / "plan.json", run.story.plan_json);
  std::string text = run.story.plan.narrative + "\n\n";
  for (const auto& k : run.result.keyframes)
    text += "- [" + std::string(k.success ? "ok" : "failed") + "] " + k.skill + ": " + k.caption +
            (k.object.empty() ? "" : " (" + k.object + ")") +
            (k.note.empty() ? "" : " — " + k.note) + "\n";
  WriteFileAtomic(partial / "story.txt", text);
  const StoryInput& in = run.story.input;
  WriteJsonFile(partial / "config.json",
                {{"input", in.input},
                 {"theme", in.theme},
                 {"scene_plan", in.scene_plan},
                 {"instruction", in.instruction},
                 {"difficulty", in.difficulty},
                 {"scene", in.scene},
                 {"policies", run.policies.string()},
                 {"video", options.video},
                 {"options", ConfigToJson(run.options)},
                 {"goal", in.goal ? nlohmann::json({in.goal->x(), in.goal->y(), in.goal->z()})
                                  : nlohmann::json()}});
  WriteJsonFile(partial / "result.json", result_json);  // last: its presence marks completion
  std::filesystem::remove_all(dir);
  std::filesystem::rename(partial, dir);
  spdlog::info("story: {}/{} keyframes succeeded, {} falls, {:.1f} s simulated; outputs in {}",
               static_cast<int>(run.result.success_rate * run.result.keyframes.size() + 0.5),
               run.result.keyframes.size(), run.result.falls, run.result.duration_s, dir.string());
  return result_json;
}

}  // namespace sims::story
