// `mechsim bench SCENE`: work-precision sweeps (tools/bench/bench.h, docs/accuracy.md), with
// --stability the stability bench (tools/bench/stability.h), with --models-alone the
// scene's stepping floor and with --peer-system its FMUs and OSP system structure for
// libcosim (tools/bench/models_alone.h, peer_system.h; tools/bench-peer.sh).
#include <cstdio>
#include <iostream>
#include <sstream>

#include "bench.h"
#include "commands.h"
#include "models_alone.h"
#include "peer_system.h"
#include "stability.h"

namespace mechsim::tools {

namespace {

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
    if (b != std::string::npos) out.push_back(item.substr(b, e - b + 1));
  }
  return out;
}

}  // namespace

void add_bench_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "bench",
      "Work-precision bench of a scene: sweeps macro step, coupling scheme, node solver and tolerance in process, "
      "with DDS spot checks; error against the reference, wall time, observed order (docs/accuracy.md)");
  auto args = std::make_shared<SceneArgs>();
  auto opt = std::make_shared<bench::BenchOptions>();
  auto steps = std::make_shared<std::string>();
  auto schemes = std::make_shared<std::string>();
  auto solvers = std::make_shared<std::string>();
  auto rtols = std::make_shared<std::string>();
  auto tolerances = std::make_shared<std::string>();
  auto stability = std::make_shared<bool>(false);
  auto models_alone = std::make_shared<bool>(false);
  auto peer_system = std::make_shared<std::string>();
  add_scene_args(cmd, *args);
  cmd->add_option("--json", opt->json_path, "write every run as a JSON row, with orders, DDS checks and provenance");
  cmd->add_option("--plots", opt->plots_dir, "write the PNG work-precision and error-against-step diagrams here");
  cmd->add_option("--steps", *steps, "macro steps to sweep, e.g. '25 us,50 us,100 us' (default: the scene's step x 1/4 .. 10)");
  cmd->add_option("--schemes", *schemes,
                  "schemes to sweep, comma separated (default: all valid for the scene's connections), e.g. "
                  "'shipped,jacobi/hold,jacobi/linear,gauss_seidel/hold,compliant/linear,interface_jacobian/10'");
  cmd->add_option("--solvers", *solvers, "node solvers, comma separated (default: cvode_bdf,cvode_adams,arkode_erk,arkode_dirk)");
  cmd->add_option("--rtol", opt->rtol, "node tolerance of the solver sweep (atol = rtol/1000)")->capture_default_str();
  cmd->add_option("--rtols", *rtols, "further node tolerances swept with cvode_bdf, comma separated (default: 1e-4,1e-8)");
  auto* tol_opt = cmd->add_option(
      "--tolerances", *tolerances,
      "coupling tolerances of the adaptive macro step (time.step: adaptive), comma separated, run with the shipped "
      "scheme, its orders with every Jacobi edge quadratic (shipped/quadratic) and the best fixed-H scheme at the "
      "scene's H, cvode_bdf at --rtol (default: 1e-2,3e-3,1e-3,3e-4,1e-4; "
      "--quick 1e-2,1e-3; 'none': no adaptive points)");
  cmd->add_option("--dds-checks", opt->dds_checks, "number of DDS spot checks through `mechsim launch` (default 2, --quick 1)");
  cmd->add_option("--repeat", opt->repeat, "time every in-process run this often and keep the fastest (default 1; runs under 0.25 s are repeated anyway, up to ten times)")
      ->check(CLI::Range(1, 100));
  cmd->add_flag("--quick", opt->quick, "a small subset for CI: the shipped, zero-order-hold and linear schemes, 3 steps, cvode_bdf");
  cmd->add_option("--work-dir", opt->work_dir, "scratch folder for run logs (default: a fresh /tmp/mechsim-bench-*)");
  cmd->add_flag("--keep", opt->keep_work_dir, "keep the scratch folder");
  cmd->add_flag("--stability", *stability,
                "instead: the largest stable macro step per connection and scheme (tools/bench/stability.h)");
  cmd->add_flag("--models-alone", *models_alone,
                "instead: one run with the node steppers called in a loop on one thread, no transport (the floor of "
                "tools/bench-peer.sh): steps/s, CPU per step, max RSS (--json writes them)");
  cmd->add_option("--peer-system", *peer_system,
                  "instead: export every participant as an FMI 2 FMU into this folder and write its OspSystemStructure.xml "
                  "for libcosim (tools/bench-peer.sh)");
  cmd->callback([=, &exit_code] {
    if (*models_alone) {
      exit_code = bench::run_models_alone(args->scene, {args->overrides(), opt->json_path}, std::cout);
      return;
    }
    if (!peer_system->empty()) {
      exit_code = bench::write_peer_system(args->scene, {args->overrides(), *peer_system}, std::cout);
      return;
    }
    if (*stability) {
#ifdef MECHSIM_HAVE_STABILITY_BENCH
      bench::StabilityOptions so;
      so.json_path = opt->json_path;
      so.plots_dir = opt->plots_dir;
      so.set_overrides = args->overrides();
      so.quick = opt->quick;
      exit_code = bench::run_stability_bench(args->scene, so, std::cout);
#else
      std::fprintf(stderr, "mechsim bench --stability: not in this build (tools/bench/stability.cpp is missing)\n");
      exit_code = 2;
#endif
      return;
    }
    bench::BenchOptions o = *opt;
    o.scene_path = args->scene;
    o.overrides = args->overrides();
    try {
      if (!steps->empty()) o.steps = bench::parse_steps(*steps);
      o.schemes = split_list(*schemes);
      o.solvers = split_list(*solvers);
      for (const auto& s : o.solvers)
        if (s != "cvode_bdf" && s != "cvode_adams" && s != "arkode_erk" && s != "arkode_dirk")
          throw std::invalid_argument("--solvers: unknown solver '" + s + "' (cvode_bdf, cvode_adams, arkode_erk, arkode_dirk)");
      for (const auto& r : split_list(*rtols)) {
        std::size_t used = 0;
        double v = 0;
        try {
          v = std::stod(r, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used != r.size() || !(v > 0) || v >= 1) throw std::invalid_argument("--rtols: expected numbers in (0, 1), got '" + r + "'");
        o.rtols.push_back(v);
      }
      if (tol_opt->count() > 0) o.tolerances = bench::parse_tolerances(*tolerances);
      if (!(o.rtol > 0) || o.rtol >= 1) throw std::invalid_argument("--rtol: expected a number in (0, 1)");
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "mechsim bench: %s\n", e.what());
      exit_code = 2;
      return;
    }
    try {
      exit_code = bench::run_bench(o, std::cout);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "mechsim bench: %s\n", e.what());
      exit_code = 1;
    }
  });
}

}  // namespace mechsim::tools
