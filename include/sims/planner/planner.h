// The planner's front door: theme or script → long script (embedded planner, or the LLM
// back-end with automatic fall-back) → layout choice and keyframe binding → Plan (plan.h).
//
//   StoryPlanner planner(LoadPlannerConfig());
//   ScriptResult s = planner.ScriptForTheme("happy at first, then depressed", Difficulty::kMid, 7);
//   Plan plan = planner.Place(s, LayoutDatabase::Load("layouts.json"));
//   SavePlan("plan.json", plan);
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sims/core/config.h"
#include "sims/planner/composer.h"
#include "sims/planner/layout.h"
#include "sims/planner/llm_client.h"
#include "sims/planner/plan.h"

namespace sims::planner {

/// All planner settings (configs/planner/planner.json).
struct PlannerConfig {
  std::string scripts_dir;                 ///< Short-script database ("" = assets/scripts).
  std::vector<std::string> extra_scripts;  ///< Script files/folders appended to the database.
  std::string vocabulary;       ///< Vocabulary file ("" = configs/planner/vocabulary.json).
  std::string emotion_lexicon;  ///< Lexicon file ("" = configs/planner/emotion_lexicon.json).
  RetrievalConfig retrieval;    ///< Retrieval weights.
  DifficultyConfig difficulty;  ///< Interaction counts per difficulty.
  LayoutConfig layout;          ///< Scene graphs, matching costs, composition.
  LlmConfig llm;                ///< Optional LLM back-end.

  /// Lists the fields for the JSON archives.
  template <class A>
  void Serialize(A* a) {
    a->Visit(SIMS_NVP(scripts_dir));
    a->Visit(SIMS_NVP(extra_scripts));
    a->Visit(SIMS_NVP(vocabulary));
    a->Visit(SIMS_NVP(emotion_lexicon));
    a->Visit(SIMS_NVP(retrieval));
    a->Visit(SIMS_NVP(difficulty));
    a->Visit(SIMS_NVP(layout));
    a->Visit(SIMS_NVP(llm));
  }
};

/// Loads configs/planner/planner.json (or `path`).
PlannerConfig LoadPlannerConfig(const std::filesystem::path& path = {});

/// A long script and who produced it.
struct ScriptResult {
  LongScript script;    ///< The keyframes (grammar repaired) and narrative.
  std::string planner;  ///< "embedded", "llm:<model>" or "script".
  std::string note;     ///< Why the LLM was not used, or other remarks.
};

/// Plans stories. Thread-compatible (one instance per thread).
class StoryPlanner {
 public:
  /// Loads the vocabulary, lexicon and short-script database the config names; `embedder`
  /// (optional) adds text-embedding similarity to retrieval.
  explicit StoryPlanner(PlannerConfig config = LoadPlannerConfig(), TextEmbedder embedder = {});
  ~StoryPlanner();

  /// Theme → long script. Uses the LLM when config.llm.endpoint is set (the apps fill it from
  /// $SIMS_LLM_ENDPOINT with WithEnvironment); on no endpoint, time-out, HTTP error or an invalid
  /// reply it falls back to the embedded planner and says why in `note`.
  ScriptResult ScriptForTheme(const std::string& theme, Difficulty difficulty, uint64_t seed) const;
  /// The embedded planner only.
  ScriptResult EmbeddedScript(const std::string& theme, Difficulty difficulty, uint64_t seed) const;
  /// The LLM back-end only; throws LlmError / sims::Error on any failure.
  ScriptResult LlmScript(const std::string& theme, Difficulty difficulty, uint64_t seed) const;
  /// A script file (any LoadLongScript form).
  ScriptResult ScriptFromFile(const std::filesystem::path& path) const;
  /// Validates an LLM reply (the message content) with the short-script loader and turns it
  /// into a long script; throws sims::Error naming "LLM reply" and the field on invalid output.
  LongScript ParseLlmReply(const std::string& content, Difficulty difficulty) const;
  /// The two prompts sent to the LLM for a theme (system, user).
  std::pair<std::string, std::string> LlmPrompts(const std::string& theme,
                                                 Difficulty difficulty) const;

  /// Chooses a layout from the database and binds every keyframe.
  Plan Place(const ScriptResult& script, const LayoutDatabase& layouts) const;
  /// Binds every keyframe to objects of a scene the caller chose (layout mode "given").
  Plan Place(const ScriptResult& script, const scene::Scene& scene) const;
  /// Loads a scene (scene::LoadSceneFile: built-in name, 3D-FRONT, ScanNet, mesh, ...) and
  /// binds to it; the plan records the source so MaterializeLayout can rebuild it.
  Plan PlaceInSceneFile(const ScriptResult& script, const std::string& scene) const;

  /// The configuration.
  const PlannerConfig& config() const { return config_; }
  /// The vocabulary in use.
  const Vocabulary& vocabulary() const { return *vocab_; }
  /// The short-script database in use.
  const ScriptDatabase& scripts() const { return *db_; }
  /// The embedded planner.
  const ThemePlanner& embedded() const { return *embedded_; }

 private:
  PlannerConfig config_;
  std::unique_ptr<Vocabulary> vocab_;
  std::unique_ptr<EmotionLexicon> lexicon_;
  std::unique_ptr<ScriptDatabase> db_;
  std::unique_ptr<ThemePlanner> embedded_;
};

/// Assembles a plan from a long script and a layout match (narrative: the script's own, e.g.
/// the LLM's, else the template narrative naming the bound furniture).
Plan BuildPlan(const ScriptResult& script, const LayoutMatch& match, const Vocabulary& vocab);

/// The built-in layout database (built-in rooms and house), indexed on the fly.
LayoutDatabase BuiltinLayoutDatabase(const LayoutConfig& config = {});

/// Everything apps/plan_story asks for.
struct PlanRequest {
  std::string theme;                       ///< Theme (exclusive with script).
  std::string script;                      ///< Script file (exclusive with theme).
  std::string difficulty = "mid";          ///< simple | mid | hard (themes only).
  uint64_t seed = 0;                       ///< Seed.
  std::string layouts;                     ///< Layout database file ("" = built-in layouts).
  std::string scene;                       ///< Bind to this scene instead of retrieving a layout.
  std::string config;                      ///< Planner config ("" = configs/planner/planner.json).
  std::string llm_endpoint;                ///< Overrides the config's endpoint.
  std::string llm_model;                   ///< Overrides the config's model.
  std::string llm_key;                     ///< Overrides the config's key.
  double llm_timeout_s = 0.0;              ///< Overrides the config's time-out when positive.
  std::vector<std::string> extra_scripts;  ///< --db: appended to the config's extra_scripts.
  /// Fills the LLM settings the config and flags leave open (WithEnvironment); the apps pass
  /// InstalledEnvironment(), the default fills nothing.
  Environment environment;
};

/// Theme or script → plan, as plan_story does it; errors name the flag or file.
Plan PlanStory(const PlanRequest& request, TextEmbedder embedder = {});

}  // namespace sims::planner
