// cullcheck fuzz: RapidCheck drives small scenes and pathological camera paths into an outside
// culling system (or built-in methods, in process: the soak run), holds its answers to the
// oracle and shrinks the first failure to a small case, written as a self-contained folder
// (scene, path, replay script, pictures). Exit 1 when a counterexample was found, 0 when the
// budget passed.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/fuzzing.hpp"

namespace cullcheck::cli {

Runner add_fuzz(CLI::App& app) {
  struct Flags {
    FuzzOptions fuzz;
    SamplingFlags sampling;
    std::string out = "cullcheck-counterexample", output, methods;
    bool no_pixels = false;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand(
      "fuzz", "Fuzz an outside culling system: seeded scenes (cities, walls with openings) and pathological camera paths "
              "(viewport edges, lateral moves past thin walls, pitch/roll, orthographic, near plane) held to the oracle; "
              "the first failure is shrunk and written as a folder that replays it. Exit 1 when one was found");
  CLI::Option* subject =
      sub->add_option("--subject", f->fuzz.subject, "The subject's command line (run by /bin/sh -c; README, subject protocol)");
  CLI::Option* methods = sub->add_option("--method", f->methods,
                                         "Or built-in methods, comma-separated or 'conservative' (every method that claims it), "
                                         "run in process: each case's oracle answer checks them all (the soak run)");
  subject->excludes(methods);
  methods->excludes(subject);
  sub->add_option("--budget", f->fuzz.budget, "Cases that must pass (RapidCheck's max_success)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000000));
  sub->add_option("--seed", f->fuzz.seed, "Seed of the cases (the same seed draws the same cases)")->capture_default_str();
  sub->add_option("--timeout", f->fuzz.frame_timeout, "Seconds the subject may take per frame")->capture_default_str();
  sub->add_option("--hello-timeout", f->fuzz.hello_timeout, "Seconds the subject may take to load a scene")->capture_default_str();
  sub->add_option("--out", f->out, "Folder for the minimal counterexample")->capture_default_str();
  sub->add_option("--output,-o", f->output, "Also write the run's summary as JSON");
  sub->add_option("--work-dir", f->fuzz.work_dir, "Folder for each case's scene files (default: a temporary one)");
  sub->add_flag("--no-pixels", f->no_pixels, "Skip the pixel oracle for conservative subjects");
  sub->add_flag("--hold-conservative", f->fuzz.hold_conservative, "Judge every built-in method as claiming conservativeness, whatever it claims: how a paper's claim the engine does not gate is checked (e.g. rdt)");
  add_shard_flag(*sub, f->fuzz.shard,
                 "Run shard K of N (e.g. 0/4) of the cases: the n-th case drawn is shard n mod N's; a shard stops at its own "
                 "first failure. Needs --output; `cullcheck merge` joins the N files into the unsharded run's summary");
  f->sampling.add(*sub);
  return [f] {
    if (f->fuzz.subject.empty() && f->methods.empty()) throw std::invalid_argument("fuzz: give --subject or --method");
    if (!f->fuzz.shard.whole() && f->output.empty()) throw InputError("flag", "shard", "needs --output: the file `cullcheck merge` joins");
    if (!f->methods.empty()) f->fuzz.methods = f->methods == "conservative" ? conservative_method_names() : parse_methods(f->methods);
    f->fuzz.sampling = f->sampling.sampling;
    f->fuzz.pixels = !f->no_pixels;
    const FuzzResult r = fuzz_subject(f->fuzz);
    // Each shard writes its own folder: shards on one machine must not overwrite each other's.
    if (!f->fuzz.shard.whole()) f->out += "-shard" + std::to_string(f->fuzz.shard.index);
    nlohmann::json doc = f->fuzz.shard.whole() ? fuzz_json(r) : fuzz_shard_json(r, f->fuzz);
    int code = 0;
    if (r.failure) {
      write_counterexample(r, f->fuzz, f->out);
      doc["counterexample"] = f->out;
      code = kExitGateFailed;
    }
    std::cout << fuzz_summary(r, f->out);
    if (!f->output.empty()) write_text_file_atomically(f->output, doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    return code;
  };
}

}  // namespace cullcheck::cli
