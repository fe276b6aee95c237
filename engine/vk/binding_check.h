// The check that keeps a pass's resource table and its shaders in agreement: at pipeline creation, the
// bindings the pass declares (vk::Binding, from its table) are compared with what each shader's SPIR-V
// declares (vk/spirv_reflect.h). A mismatch is a vct::Error naming the pass, the binding and both sides, e.g.
//   trace: binding 8 (guideAxis): the pass binds a storage image rgba16f, trace.comp declares a storage image
//   rgba32f ('guideAxisImage')
#pragma once

#include <string>
#include <vector>

#include "vk/pipeline.h"
#include "vk/spirv_reflect.h"

namespace vct::vk {

struct ShaderInterface {
    VkShaderStageFlagBits stage;
    std::string shader;  // its file name, for messages
    std::vector<ShaderBinding> bindings;
};

// Throws unless, for every descriptor a shader declares: it is in set 0; the pass declares that binding, for
// a stage set that includes the shader's, with the same descriptor type; a storage image has the format of
// the pass's image; a sampled or storage image has its dimension (2D, 3D) and numeric class (float, uint,
// int); a shadow sampler is bound with a depth-comparison sampler and only then. And every binding the pass
// declares for one of these stages is declared by one of the shaders (a stale row is as wrong as a missing
// one).
void checkBindings(const std::string& owner, const std::vector<Binding>& declared,
                   const std::vector<ShaderInterface>& shaders);

}  // namespace vct::vk
