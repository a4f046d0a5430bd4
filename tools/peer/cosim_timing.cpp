// Times libcosim's stepping of an OspSystemStructure.xml, for tools/bench-peer.sh.
// cosim-cli prints no timing, so this loads the structure the way its `run` does
// (fixed-step algorithm from the file, no file observer) and times execution::simulate_until
// alone: loading and instantiating the FMUs is start-up, not stepping.
//   cosim_timing SYSTEM_STRUCTURE.xml DURATION_S [WORKER_THREADS=0] [JSON_OUT]
// Built by tools/build-peer-libcosim.sh against libcosim 0.11.2; not part of mechsim's build.
#include <cosim/algorithm/fixed_step_algorithm.hpp>
#include <cosim/execution.hpp>
#include <cosim/log/simple.hpp>
#include <cosim/orchestration.hpp>
#include <cosim/osp_config_parser.hpp>
#include <cosim/time.hpp>

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
double cpu_seconds()
{
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
        1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}
} // namespace

int main(int argc, char** argv)
{
    if (argc < 3) {
        std::cerr << "usage: cosim_timing SYSTEM_STRUCTURE.xml DURATION_S [WORKER_THREADS=0] [JSON_OUT]\n";
        return 2;
    }
    const std::string structure = argv[1];
    const double duration = std::atof(argv[2]);
    const unsigned workers = argc > 3 ? static_cast<unsigned>(std::atoi(argv[3])) : 0u;
    const std::string json_out = argc > 4 ? argv[4] : "";
    try {
        cosim::log::setup_simple_console_logging();
        cosim::log::set_global_output_level(cosim::log::warning);
        const auto resolver = cosim::default_model_uri_resolver();
        const auto config = cosim::load_osp_config(structure, *resolver);
        const auto* fixed = std::get_if<cosim::fixed_step_algorithm_params>(&config.algorithm_configuration);
        if (fixed == nullptr) {
            std::cerr << "cosim_timing: only <Algorithm>fixedStep is timed\n";
            return 2;
        }
        const double step = cosim::to_double_duration(fixed->stepSize, config.start_time);
        auto algorithm = std::make_shared<cosim::fixed_step_algorithm>(*fixed, workers);
        cosim::execution execution(config.start_time, algorithm);
        cosim::inject_system_structure(execution, config.system_structure, config.initial_values);
        execution.initialize();

        const auto end = config.start_time + cosim::to_duration(duration);
        const double cpu_before = cpu_seconds();
        const auto wall_before = std::chrono::steady_clock::now();
        execution.simulate_until(end);
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_before).count();
        const double cpu = cpu_seconds() - cpu_before;

        const double reached = cosim::to_double_time_point(execution.current_time());
        const long long steps = std::llround(reached / step);
        rusage usage{};
        getrusage(RUSAGE_SELF, &usage);
        std::printf("libcosim %s: %lld steps in %.4f s wall, %.4f s CPU: %.0f steps/s, %.3f us CPU/step, max RSS %ld kB\n",
            structure.c_str(), steps, wall, cpu, steps / wall, 1e6 * cpu / steps, usage.ru_maxrss);
        if (!json_out.empty()) {
            std::ofstream json(json_out);
            json << "{\"steps\": " << steps << ", \"wall_s\": " << wall << ", \"cpu_s\": " << cpu
                 << ", \"steps_per_s\": " << steps / wall << ", \"worker_threads\": " << workers
                 << ", \"max_rss_kb\": " << usage.ru_maxrss << "}\n";
        }
    } catch (const std::exception& e) {
        std::cerr << "cosim_timing: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
