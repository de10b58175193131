// Shows how a caption is understood: its 64-d style embedding z and the nearest training
// captions and clips by cosine similarity.
//   text_to_style "a person walks sadly" [--model data/language/text_motion] [--top 5] [--json]
//   text_to_style --eval configs/language/dev_paraphrases.json
#include <iostream>

#include <CLI/CLI.hpp>

#include "sims/core/app.h"
#include "sims/core/error.h"
#include "sims/core/paths.h"
#include "sims/language/embedding_bank.h"
#include "sims/language/retrieval_eval.h"

int main(int argc, char** argv) {
  CLI::App app{"Caption -> style embedding z, with the nearest training captions and clips"};
  std::string caption, model_dir = sims::language::DefaultStyleModelDir().string(), eval;
  int top = 5;
  bool as_json = false;
  sims::AppFlags flags;
  app.add_option("caption", caption, "the caption to embed");
  app.add_option("--eval", eval, "held-out paraphrase file: print retrieval accuracy instead");
  app.add_option("--model", model_dir, "train_text_motion output folder");
  app.add_option("--top", top, "how many neighbours to list")->check(CLI::PositiveNumber);
  app.add_flag("--json", as_json, "print JSON instead of text");
  sims::AddAppFlags(&app, &flags);
  CLI11_PARSE(app, argc, argv);
  flags.default_log_level = "warn";  // model-loading info lines would bury the answer
  return sims::RunApp(flags, [&] {
    const auto embedder = sims::language::StyleEmbedder::Load(model_dir);
    if (!eval.empty()) {
      const auto r = sims::language::EvaluateRetrieval(embedder, eval);
      if (as_json) {
        std::cout << r.dump(2) << "\n";
      } else {
        for (const auto& q : r["queries"])
          std::cout << (q["correct"].get<bool>() ? "  ok   " : "  MISS ")
                    << q["caption"].get<std::string>() << " -> "
                    << q["retrieved"].get<std::string>() << " (expected "
                    << q["expected"].get<std::string>() << ")\n";
        std::cout << "retrieval accuracy: " << r["correct"] << "/" << r["total"] << " = "
                  << r["accuracy"].get<double>() << "\n";
      }
      return 0;
    }
    if (caption.empty()) throw sims::Error("caption: expected a caption to embed (or --eval FILE)");
    const auto query = embedder.Lookup(caption, top);
    if (as_json)
      std::cout << sims::language::StyleQueryToJson(query).dump(2) << "\n";
    else
      std::cout << "text encoder: " << embedder.encoder().Describe() << "\n"
                << sims::language::FormatStyleQuery(query);
    return 0;
  });
}
