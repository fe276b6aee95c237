// The subcommands of the vct program that need no window and measure nothing (the demo is
// app/demo/demo_command.h, the benchmark app/bench/benchmark_command.h). Each returns the process exit code;
// errors are thrown (vct::UsageError → 2, vct::Error → 1) and printed as one line by main().
#pragma once

namespace vct {

int runRenderCommand(int argc, char** argv, int first);
int runScenesCommand(int argc, char** argv, int first);
int runVoxelizeCommand(int argc, char** argv, int first);
int runCompareCommand(int argc, char** argv, int first);
int runExportSceneCommand(int argc, char** argv, int first);
int runReferenceCommand(int argc, char** argv, int first);

}  // namespace vct
