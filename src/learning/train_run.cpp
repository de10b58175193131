#include "sims/learning/train_run.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include "sims/core/error.h"
#include "sims/core/log.h"
#include "sims/core/progress.h"
#include "sims/io/training_report.h"
#include "sims/learning/motion_demo.h"
#include "sims/learning/sim_vec_env.h"
#include "sims/learning/text_styles.h"
#include "sims/learning/trainer.h"

namespace sims::learning {

void TrainConfig::Validate() const {
  Require(iterations > 0, "iterations", "a positive count");
  Require(checkpoint_every > 0, "checkpoint_every", "a positive count");
}

namespace {

const std::vector<std::string>& CsvColumns() {
  static const std::vector<std::string> cols = {"iteration",
                                                "samples",
                                                "task_reward",
                                                "style_reward",
                                                "total_reward",
                                                "episode_return",
                                                "episode_length",
                                                "episodes",
                                                "success_rate",
                                                "fall_rate",
                                                "actor_loss",
                                                "critic_loss",
                                                "bounds_loss",
                                                "disc_loss",
                                                "grad_penalty",
                                                "disc_acc_demo",
                                                "disc_acc_agent",
                                                "clip_fraction",
                                                "env_samples_per_s",
                                                "train_samples_per_s",
                                                "update_gflops",
                                                "iteration_seconds",
                                                "samples_per_s",
                                                "env_seconds",
                                                "inference_seconds",
                                                "disc_seconds",
                                                "ppo_seconds",
                                                "logging_seconds",
                                                "force_end_rate",
                                                "reference_start_share",
                                                "success_rate_reference",
                                                "success_rate_default",
                                                "kl",
                                                "learning_rate",
                                                "curriculum_level",
                                                "smooth_loss"};
  return cols;
}

std::string CsvRow(const IterationStats& s, const IterationTiming& timing) {
  const double v[] = {static_cast<double>(s.iteration),
                      static_cast<double>(s.samples),
                      s.task_reward,
                      s.style_reward,
                      s.total_reward,
                      s.episode_return,
                      s.episode_length,
                      static_cast<double>(s.episodes),
                      s.success_rate,
                      s.fall_rate,
                      s.actor_loss,
                      s.critic_loss,
                      s.bounds_loss,
                      s.disc_loss,
                      s.grad_penalty,
                      s.disc_acc_demo,
                      s.disc_acc_agent,
                      s.clip_fraction,
                      s.env_samples_per_s,
                      s.train_samples_per_s,
                      s.update_gflop / std::max(s.update_seconds, 1e-9),
                      s.iteration_seconds,
                      timing.samples_per_s,
                      s.env_seconds,
                      s.inference_seconds,
                      s.disc_seconds,
                      s.ppo_seconds,
                      timing.logging_seconds,
                      s.force_end_rate,
                      s.reference_start_share,
                      s.success_rate_reference,
                      s.success_rate_default,
                      s.kl,
                      s.learning_rate,
                      s.curriculum_level,
                      s.smooth_loss};
  std::ostringstream out;
  out.precision(7);
  for (size_t i = 0; i < std::size(v); ++i) out << (i ? "," : "") << v[i];
  return out.str();
}

std::string CsvHeader() {
  std::string header;
  for (const auto& c : CsvColumns()) header += (header.empty() ? "" : ",") + c;
  return header;
}

// The iteration cell of a log row: all digits (std::stoll would also take "7x" or "2.5" as 7
// and 2, and throws std::invalid_argument, not a project error, on others).
std::optional<int64_t> ParseIteration(const std::string& cell) {
  int64_t v = 0;
  const char* end = cell.data() + cell.size();
  const auto [ptr, ec] = std::from_chars(cell.data(), end, v);
  if (cell.empty() || ec != std::errc() || ptr != end || v < 0) return std::nullopt;
  return v;
}

// After a crash the log may hold rows past the last checkpoint; drop them so the resumed run
// appends exactly once per iteration. A last line without its newline was cut off mid-write
// by the crash and is dropped too. A log of an older layout (fewer trailing columns) gets the
// current header; its short rows read as missing values.
void TruncateLog(const std::filesystem::path& csv, int64_t last_iteration) {
  std::ifstream in(csv, std::ios::binary);
  if (!in) return;
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!text.empty() && text.back() != '\n') text.erase(text.rfind('\n') + 1);
  std::istringstream lines(text);
  std::string line, kept;
  bool header = true;
  int64_t lineno = 0;
  while (std::getline(lines, line)) {
    ++lineno;
    if (header) {
      const std::string current = CsvHeader();
      if (current.compare(0, line.size(), line) != 0)
        ThrowInputError(csv.string(), "line 1", "the train_policy log header (" + current + ")",
                        line);
      kept += current + "\n";
      header = false;
      continue;
    }
    if (line.empty()) continue;
    const std::string cell = line.substr(0, line.find(','));
    const std::optional<int64_t> iteration = ParseIteration(cell);
    if (!iteration)
      ThrowInputError(csv.string(), "line " + std::to_string(lineno) + ", column iteration",
                      "a non-negative integer (the log train_policy writes)", "'" + cell + "'");
    if (*iteration <= last_iteration) kept += line + "\n";
  }
  if (header) kept = CsvHeader() + "\n";  // not even the header survived
  WriteFileAtomic(csv, kept);
}

}  // namespace

PolicyConfigs ReadPolicyConfigs(const Policy& policy, const std::string& source) {
  const auto meta = nlohmann::json::parse(policy.metadata_json());
  if (!meta.contains("extra") || !meta["extra"].contains("skill"))
    ThrowInputError(source, "metadata.extra.skill",
                    "the skill config train_policy stores with a policy", "none");
  PolicyConfigs c;
  c.skill = ConfigFromJson<task::SkillConfig>(meta["extra"]["skill"], source + " (extra.skill)");
  if (meta["extra"].contains("env"))
    c.env = ConfigFromJson<sim::EnvConfig>(meta["extra"]["env"], source + " (extra.env)");
  return c;
}

std::shared_ptr<const DemoSource> MakeTrainingDemos(const TrainConfig& config,
                                                    const task::SkillSetup& setup) {
  if (!config.learner.amp.enabled || !setup.context.motions) return nullptr;
  return std::make_shared<MotionDemoSource>(
      setup.context.motions, config.learner.amp.conditional ? setup.context.styles : nullptr,
      config.env.amp_history, 1, config.skill.balance_emotions);
}

int64_t RunTraining(TrainConfig config, const TrainOptions& options) {
  const auto& out = options.out_dir;
  const auto config_path = out / "config.json";
  const auto ckpt_path = out / "checkpoint.pt";
  const auto csv_path = out / "log.csv";
  const int rank = options.comm ? options.comm->rank() : 0;
  const int world = options.comm ? options.comm->world_size() : 1;
  const bool writer = rank == 0;
  if (writer) {
    if (options.resume) {
      if (!std::filesystem::exists(ckpt_path))
        ThrowInputError(ckpt_path.string(), "", "a checkpoint to resume from (--resume)", "none");
      // Resume with exactly the configuration the run started with.
      config = LoadConfig<TrainConfig>(config_path);
    } else {
      if (options.seed) {
        config.env.seed = *options.seed;
        config.learner.seed = *options.seed;
      }
    }
    if (options.skill && *options.skill != config.skill.skill)
      ThrowInputError("--skill", "skill", "the skill of the config ('" + config.skill.skill + "')",
                      "'" + *options.skill + "'");
    if (options.iterations) config.iterations = *options.iterations;
    task::ResolveSkillParams(&config.skill);
    ValidateConfig(config, config_path.string());
  }
  if (options.comm) {
    // Every rank trains with rank 0's resolved config (the others need no copy of out_dir).
    std::string text = writer ? ConfigToJson(config).dump() : std::string();
    options.comm->Broadcast(&text, 0);
    if (!writer)
      config = ConfigFromJson<TrainConfig>(nlohmann::json::parse(text), "rank 0's config");
  }
  if (writer) {
    std::filesystem::create_directories(out);
    if (!options.resume) SaveConfig(config_path, config);
    WriteJsonFile(out / "ranks.json", {{"world_size", world},
                                       {"envs_per_rank", config.env.num_envs},
                                       {"check_every", options.check_every}});
  }

  // One scene for all ranks (it follows the run seed); environment streams follow the global
  // env id, rank × num_envs + i, as in one process with every rank's environments.
  auto setup =
      task::CreateSkill(config.skill, config.env.num_envs, config.env.seed, nullptr, &config.env);
  ApplyStyleModel(config.skill, &setup);
  sim::EnvConfig env_config = config.env;
  env_config.seed += static_cast<uint64_t>(rank) * static_cast<uint64_t>(config.env.num_envs);
  auto env = std::make_shared<sim::BatchedEnv>(setup.context.humanoid, env_config, setup.skill);
  auto vec = std::make_shared<SimVecEnv>(env);
  std::shared_ptr<const DemoSource> demo = MakeTrainingDemos(config, setup);
  if (config.learner.amp.enabled && !demo)
    ThrowInputError(config_path.string(), "skill.motion.manifest",
                    "a motion manifest when learner.amp.enabled is true", "none");
  Trainer trainer(vec, demo, config.learner, options.comm, options.check_every);
  if (writer) {
    if (options.resume) {
      trainer.LoadCheckpoint(ckpt_path);
      TruncateLog(csv_path, trainer.iteration());
      spdlog::info("resumed {} at iteration {}", out.string(), trainer.iteration());
    } else {
      if (!options.init_policy.empty()) {
        trainer.InitFromPolicy(options.init_policy);
        WriteJsonFile(out / "init_policy.json", {{"policy", options.init_policy.string()}});
        spdlog::info("actor/critic initialised from {}", options.init_policy.string());
      }
      if (!options.init_from.empty()) {
        trainer.LoadCheckpoint(options.init_from);
        WriteJsonFile(out / "init_from.json", {{"checkpoint", options.init_from.string()},
                                               {"iteration", trainer.iteration()}});
        spdlog::info("warm start from {} (iteration {})", options.init_from.string(),
                     trainer.iteration());
      }
      WriteFileAtomic(csv_path, CsvHeader() + "\n");
    }
  }
  trainer.Synchronize();
  const nlohmann::json extra = {{"skill", ConfigToJson(config.skill)},
                                {"env", ConfigToJson(config.env)}};
  auto save_all = [&]() {
    if (!writer) return;
    trainer.SaveCheckpoint(ckpt_path);
    // What a campaign commits between sessions (no replay buffer, no optimiser moments;
    // --resume accepts it).
    trainer.SaveCheckpoint(out / "checkpoint_compact.pt", /*full=*/false);
    trainer.ExportPolicy(out / "policy.pt", extra.dump());
    io::WriteTrainingReport(csv_path, out / "report.html", "train_policy " + config.skill.skill);
  };

  std::optional<ProgressReporter> progress;
  if (writer)
    progress.emplace("train " + config.skill.skill, config.iterations, "it", 10.0,
                     trainer.iteration());
  const int64_t start = trainer.iteration();
  std::ofstream csv;
  if (writer) csv.open(csv_path, std::ios::app);
  const double batch = static_cast<double>(config.learner.ppo.horizon) *
                       static_cast<double>(config.env.num_envs) * world;
  // samples/s as a user feels it: each row's interval runs from the end of the previous
  // iteration's update to the end of this one, so it holds the previous row's logging and
  // checkpoint too.
  auto last_end = std::chrono::steady_clock::now();
  const auto run_start = last_end;
  double logging_s = 0;
  for (int64_t it = start; it < config.iterations; ++it) {
    const IterationStats s = trainer.RunIteration();
    const auto end = std::chrono::steady_clock::now();
    IterationTiming timing;
    timing.interval_seconds = std::chrono::duration<double>(end - last_end).count();
    timing.logging_seconds = logging_s;
    timing.samples_per_s = batch / std::max(timing.interval_seconds, 1e-9);
    last_end = end;
    if (writer) {
      csv << CsvRow(s, timing) << "\n";
      csv.flush();
      char extra_text[200];
      const double elapsed = std::chrono::duration<double>(end - run_start).count();
      std::snprintf(extra_text, sizeof(extra_text),
                    "reward %.3f (task %.3f style %.3f) success %.2f falls %.2f ep_len %.0f, "
                    "%.0f samples/s (mean %.0f)",
                    s.total_reward, s.task_reward, s.style_reward, s.success_rate, s.fall_rate,
                    s.episode_length, timing.samples_per_s,
                    batch * static_cast<double>(it + 1 - start) / std::max(elapsed, 1e-9));
      progress->Update(it + 1, extra_text);
    }
    if ((it + 1) % config.checkpoint_every == 0) save_all();
    logging_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - end).count();
    if (options.on_iteration) options.on_iteration(s, timing);
  }
  save_all();
  if (progress) progress->Finish();
  return trainer.iteration();
}

}  // namespace sims::learning
