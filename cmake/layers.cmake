# The engine's layers, lowest first: one CMake library each (CMakeLists.txt), and the only includes allowed
# between them (cmake/check_layers.cmake, run by the build and by ctest). A layer may include its own headers
# and those of the layers it DEPENDS on, directly or through them; never one declared after it. So the order
# of this list is the order of the layers, and a cycle cannot be written down.
#
#   VCT_LAYER_<name>_DIRS     its folders, relative to engine/ (shaders/lib is "lib": the GPU-shared headers,
#                             included as "lib/NAME" from the -I of shaders/)
#   VCT_LAYER_<name>_DEPENDS  the layers below it that it uses directly
set(VCT_LAYERS gpu core vk scene io render reference report app_cli app_bench app_demo app)

set(VCT_LAYER_gpu_DIRS lib)  # shaders/lib: C++/GLSL structs and constants, GLSL math included by render code
set(VCT_LAYER_gpu_DEPENDS "")
set(VCT_LAYER_core_DIRS core)  # errors, the vertex layout
set(VCT_LAYER_core_DEPENDS "")
set(VCT_LAYER_vk_DIRS vk)  # Vulkan: device, buffers, images, pipelines, reflection of a shader's bindings
set(VCT_LAYER_vk_DEPENDS core)
set(VCT_LAYER_scene_DIRS scene)  # the scene in memory, glTF in and out, built-in scenes, cameras, input limits
set(VCT_LAYER_scene_DEPENDS gpu core)  # gpu: the deformation math shared with skin.comp
set(VCT_LAYER_io_DIRS io)  # files without a renderer: EXR/PNG images, OpenVDB voxel files, safe writes
set(VCT_LAYER_io_DEPENDS gpu core scene)
set(VCT_LAYER_render_DIRS render passes)  # the frame: renderer, frame targets, voxel grid, the passes
set(VCT_LAYER_render_DEPENDS gpu core vk scene io)
set(VCT_LAYER_reference_DIRS reference)  # the path-traced ground truth (Embree, CPU)
set(VCT_LAYER_reference_DEPENDS core scene io render)
set(VCT_LAYER_report_DIRS report)  # what is measured, as files: timings/settings JSON, error metrics
set(VCT_LAYER_report_DEPENDS core vk scene io render)
set(VCT_LAYER_app_cli_DIRS app/cli)  # the program's options, session and headless commands
set(VCT_LAYER_app_cli_DEPENDS core vk scene io render reference report)
set(VCT_LAYER_app_bench_DIRS app/bench)  # vct benchmark: its modes as build / run / report steps
set(VCT_LAYER_app_bench_DEPENDS app_cli)
set(VCT_LAYER_app_demo_DIRS app/demo)  # vct demo: window, panel (Dear ImGui, GLFW), controls
set(VCT_LAYER_app_demo_DEPENDS app_cli)
set(VCT_LAYER_app_DIRS app)  # main.cpp: dispatches the commands
set(VCT_LAYER_app_DEPENDS app_cli app_bench app_demo)
