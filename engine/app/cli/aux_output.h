// `vct render --aux` and `--view`: every intermediate buffer as EXR, and which buffer final.png shows.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "render/renderer.h"

namespace vct {

// What final.png shows: the composited frame or one intermediate buffer.
// Voxels: the voxel grid ray-marched at one mip (Renderer::renderVoxelView), not a buffer of the frame.
// Resample and Weights: the upsampling's re-traced pixels and sum of weights (app/cli/upsample_views.h).
enum class AuxView { Final, Direct, Diffuse, Specular, Normals, Roughness, Voxels, Resample, Weights };

// Parses a --view value; throws UsageError for unknown ones and for those not implemented yet.
AuxView parseAuxView(const std::string& value);
const char* auxViewName(AuxView view);  // the --view value
// The views of buffers that only exist with GI on (indirect light, upsampling weights, the voxel grid).
bool auxViewNeedsGi(AuxView view);

// Writes direct, diffuse_indirect, specular_indirect (when the frame targets have them), normal, roughness,
// albedo and depth as EXR into `dir`; returns the names written.
std::vector<std::string> writeAuxImages(Renderer& renderer, const std::filesystem::path& dir);

// Writes the frame's linear HDR final image as `path` (vct render's final.exr).
void writeFinalExr(Renderer& renderer, const std::filesystem::path& path);

// What `vct compare --reference-dir` measures, read back as `vct render --aux` does: final.exr, direct.exr,
// diffuse_indirect.exr and specular_indirect.exr (the last two only with GI on) into `dir`; returns the names
// written. The report mode's last frames (vct benchmark --mode report --dump-last).
std::vector<std::string> writeLightImages(Renderer& renderer, const std::filesystem::path& dir);

// RGBA8 for final.png: the LDR frame for AuxView::Final, else the buffer encoded for display (radiance
// exposed, tone mapped and sRGB-encoded like the composite; normals as n·0.5 + 0.5; roughness grey).
// AuxView::Voxels renders the voxel view at `voxelMip` first (valid mips: see Renderer::renderVoxelView).
std::vector<uint8_t> viewImage(Renderer& renderer, AuxView view, uint32_t voxelMip = 0);

}  // namespace vct
