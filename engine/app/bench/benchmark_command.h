// vct benchmark: the subcommand (its modes: app/bench/benchmark_modes.h). Returns the process exit code;
// errors are thrown (vct::UsageError → 2, vct::Error → 1) and printed as one line by main().
#pragma once

namespace vct {

int runBenchmarkCommand(int argc, char** argv, int first);

}  // namespace vct
