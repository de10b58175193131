#include "sims/story/story.h"

#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <utility>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/paths.h"
#include "sims/eval/style_classifier.h"
#include "sims/io/story_outputs.h"
#include "sims/language/embedding_bank.h"
#include "sims/language/retrieval_eval.h"
#include "sims/motion/motion_library.h"
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
                                          ? language::DefaultStyleModelDir()
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
  return std::move(RunStories({story}, policies, {options}, nullptr, 1).front());
}

std::vector<StoryRun> RunStories(const std::vector<PreparedStory>& stories,
                                 const fsm::PolicySet& policies,
                                 const std::vector<fsm::StoryOptions>& options,
                                 std::vector<std::exception_ptr>* errors, int threads) {
  SIMS_CHECK_MSG(stories.size() == options.size(), "one set of FSM options per story");
  const size_t n = stories.size();
  std::vector<std::exception_ptr> failed(n);
  std::vector<std::unique_ptr<fsm::StoryRunner>> runners(n);
  std::vector<std::unique_ptr<io::MotionRecordBuilder>> recorders(n);
  std::vector<fsm::StoryJob> jobs;
  std::vector<size_t> job_story;  // story of each job
  // Set-up one story after another: it loads policies (libtorch) and compiles scenes.
  for (size_t i = 0; i < n; ++i) {
    const PreparedStory& story = stories[i];
    try {
      runners[i] = std::make_unique<fsm::StoryRunner>(story.scene, policies, options[i]);
      runners[i]->CheckPolicies(story.instructions);
      fsm::StoryJob job;
      job.runner = runners[i].get();
      job.instructions = &story.instructions;
      job.start = runners[i]->DefaultStart(story.instructions);
      recorders[i] = std::make_unique<io::MotionRecordBuilder>(runners[i]->humanoid());
      recorders[i]->SetTitle(story.title);
      recorders[i]->SetScene(
          {story.scene->name, story.plan.layout.mode == "given" ? story.input.scene : ""});
      job.recorder = recorders[i].get();
      jobs.push_back(job);
      job_story.push_back(i);
    } catch (...) {
      failed[i] = std::current_exception();
    }
  }
  std::vector<std::exception_ptr> job_errors;
  std::vector<fsm::StoryResult> results = fsm::RunStoriesBatched(jobs, threads, &job_errors);
  std::vector<StoryRun> runs(n);
  for (size_t i = 0; i < n; ++i) runs[i].story = stories[i];
  for (size_t j = 0; j < jobs.size(); ++j) {
    const size_t i = job_story[j];
    if (job_errors[j]) {
      failed[i] = job_errors[j];
      continue;
    }
    StoryRun& run = runs[i];
    run.result = std::move(results[j]);
    run.record = recorders[i]->Finish();
    run.policies = policies.source;
    run.options = options[i];
    run.geometry = std::make_shared<const humanoid::StaticGeometry>(runners[i]->geometry());
    run.humanoid = runners[i]->humanoid();
    runners[i].reset();  // frees the scene's model and environment before the next ones
  }
  if (errors) {
    *errors = std::move(failed);
  } else {
    for (const auto& e : failed)
      if (e) std::rethrow_exception(e);
  }
  return runs;
}

namespace {

// Per script keyframe: the caption, the emotion the script gives it, the emotion of the clip
// its z is nearest to, and the style a classifier trained on the synthetic clips of that skill
// measures in the keyframe's motion ("" where it cannot: no clips of two emotions, or under
// 3 s of motion).
nlohmann::json KeyframeStyles(const StoryRun& run) {
  nlohmann::json out = nlohmann::json::array();
  // The clips and per-skill classifiers are built once per process: an evaluation writes many
  // stories, and training the classifiers for each story cost more than running it.
  static std::mutex mu;
  static std::unique_ptr<motion::MotionLibrary> lib;
  static std::map<std::string, std::unique_ptr<eval::StyleClassifier>> classifiers;
  static bool loaded = false;
  std::lock_guard<std::mutex> lock(mu);
  if (!loaded && run.humanoid) {
    loaded = true;
    const std::filesystem::path manifest = DataPath("motions/synthetic/manifest.json");
    if (std::filesystem::exists(manifest))
      lib = std::make_unique<motion::MotionLibrary>(
          motion::MotionLibrary::Load(manifest, run.humanoid));
  }
  std::map<std::string, std::string> emotion_of;  // clip name → emotion
  if (lib)
    for (int i = 0; i < lib->num_clips(); ++i)
      emotion_of[lib->clip(i).meta().name] = lib->clip(i).meta().emotion;
  // A bank key names a clip style (mirror and variant suffixes, ClipStyleOf strips them); every
  // variant and mirror of a style carries its emotion.
  auto emotion_of_key = [&](const std::string& key) -> std::string {
    const auto it = emotion_of.find(language::ClipStyleOf(key));
    return it == emotion_of.end() ? "" : it->second;
  };
  auto classifier = [&](const std::string& skill) -> const eval::StyleClassifier* {
    auto it = classifiers.find(skill);
    if (it != classifiers.end()) return it->second.get();
    std::unique_ptr<eval::StyleClassifier> c;
    if (lib) {
      std::vector<const motion::MotionClip*> clips;
      std::set<std::string> emotions;
      for (int i = 0; i < lib->num_clips(); ++i)
        if (lib->clip(i).meta().skill == skill && !eval::IsClipVariant(lib->clip(i).meta()) &&
            lib->clip(i).num_frames() >= 60) {
          clips.push_back(&lib->clip(i));
          emotions.insert(lib->clip(i).meta().emotion);
        }
      if (emotions.size() >= 2)
        c = std::make_unique<eval::StyleClassifier>(eval::StyleClassifier::Train(clips));
    }
    return (classifiers[skill] = std::move(c)).get();
  };
  const auto& instructions = run.story.instructions;
  for (const io::KeyframeAnnotation& k : run.record.keyframes) {
    nlohmann::json e = {{"keyframe", k.index},  {"skill", k.skill},     {"caption", k.caption},
                        {"emotion", k.emotion}, {"z_nearest_clip", ""}, {"z_emotion", ""},
                        {"measured_style", ""}};
    for (size_t i = 0; i < instructions.size() && i < run.story.styles.size(); ++i) {
      if (instructions[i].keyframe != k.index) continue;
      const auto& clips = run.story.styles[i]["clips"];
      if (!clips.empty()) {
        const std::string clip = clips[0]["clip"];
        e["z_nearest_clip"] = clip;
        e["z_emotion"] = emotion_of_key(clip);
      }
      break;
    }
    const eval::StyleClassifier* c = k.start_frame >= 0 ? classifier(k.skill) : nullptr;
    if (c) {
      std::vector<motion::MotionFrame> frames;
      for (int f = k.start_frame; f <= k.end_frame && f < run.record.num_frames(); ++f) {
        const io::RecordFrame& r = run.record.frames[f];
        motion::MotionFrame m;
        m.root_pos = r.root_pos;
        m.root_rot = r.root_rot;
        m.dof_pos = r.dof_pos;
        frames.push_back(m);
      }
      const int label = c->Classify(frames);
      if (label >= 0) e["measured_style"] = c->labels()[label];
    }
    out.push_back(e);
  }
  return out;
}

}  // namespace

nlohmann::json StoryRunToJson(const StoryRun& run) {
  nlohmann::json j = fsm::StoryResultToJson(run.result);
  j["planner"] = run.story.plan.planner;
  j["planner_note"] = run.story.plan.planner_note;
  j["scene"] = run.story.scene->name;
  j["seed"] = run.options.seed;
  j["policies"] = run.policies.string();
  j["styles"] = run.story.styles;
  j["keyframe_styles"] = KeyframeStyles(run);
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
