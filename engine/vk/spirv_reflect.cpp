#include "vk/spirv_reflect.h"

#include <unordered_map>

#include "core/error.h"

namespace vct::vk {

namespace {

// The few SPIR-V enumerants this reads (SPIR-V 1.6 specification, §3).
constexpr uint32_t kMagic = 0x07230203;
enum Op : uint32_t {
    OpName = 5,
    OpTypeInt = 21,
    OpTypeFloat = 22,
    OpTypeImage = 25,
    OpTypeSampler = 26,
    OpTypeSampledImage = 27,
    OpTypeArray = 28,
    OpTypeRuntimeArray = 29,
    OpTypeStruct = 30,
    OpTypePointer = 32,
    OpVariable = 59,
    OpDecorate = 71,
};
enum Decoration : uint32_t { Block = 2, BufferBlock = 3, Binding = 33, DescriptorSet = 34 };
enum StorageClass : uint32_t { UniformConstant = 0, Uniform = 2, StorageBuffer = 12 };
enum Dim : uint32_t { Dim1D = 0, Dim2D = 1, Dim3D = 2, DimCube = 3, DimBuffer = 5, DimSubpassData = 6 };

// SPIR-V's ImageFormat (its index in this table) ↔ Vulkan format ↔ GLSL layout qualifier.
struct FormatName {
    VkFormat format;
    const char* glsl;
};
constexpr FormatName kImageFormats[] = {
    {VK_FORMAT_UNDEFINED, "no format"},
    {VK_FORMAT_R32G32B32A32_SFLOAT, "rgba32f"},
    {VK_FORMAT_R16G16B16A16_SFLOAT, "rgba16f"},
    {VK_FORMAT_R32_SFLOAT, "r32f"},
    {VK_FORMAT_R8G8B8A8_UNORM, "rgba8"},
    {VK_FORMAT_R8G8B8A8_SNORM, "rgba8_snorm"},
    {VK_FORMAT_R32G32_SFLOAT, "rg32f"},
    {VK_FORMAT_R16G16_SFLOAT, "rg16f"},
    {VK_FORMAT_B10G11R11_UFLOAT_PACK32, "r11f_g11f_b10f"},
    {VK_FORMAT_R16_SFLOAT, "r16f"},
    {VK_FORMAT_R16G16B16A16_UNORM, "rgba16"},
    {VK_FORMAT_A2B10G10R10_UNORM_PACK32, "rgb10_a2"},
    {VK_FORMAT_R16G16_UNORM, "rg16"},
    {VK_FORMAT_R8G8_UNORM, "rg8"},
    {VK_FORMAT_R16_UNORM, "r16"},
    {VK_FORMAT_R8_UNORM, "r8"},
    {VK_FORMAT_R16G16B16A16_SNORM, "rgba16_snorm"},
    {VK_FORMAT_R16G16_SNORM, "rg16_snorm"},
    {VK_FORMAT_R8G8_SNORM, "rg8_snorm"},
    {VK_FORMAT_R16_SNORM, "r16_snorm"},
    {VK_FORMAT_R8_SNORM, "r8_snorm"},
    {VK_FORMAT_R32G32B32A32_SINT, "rgba32i"},
    {VK_FORMAT_R16G16B16A16_SINT, "rgba16i"},
    {VK_FORMAT_R8G8B8A8_SINT, "rgba8i"},
    {VK_FORMAT_R32_SINT, "r32i"},
    {VK_FORMAT_R32G32_SINT, "rg32i"},
    {VK_FORMAT_R16G16_SINT, "rg16i"},
    {VK_FORMAT_R8G8_SINT, "rg8i"},
    {VK_FORMAT_R16_SINT, "r16i"},
    {VK_FORMAT_R8_SINT, "r8i"},
    {VK_FORMAT_R32G32B32A32_UINT, "rgba32ui"},
    {VK_FORMAT_R16G16B16A16_UINT, "rgba16ui"},
    {VK_FORMAT_R8G8B8A8_UINT, "rgba8ui"},
    {VK_FORMAT_R32_UINT, "r32ui"},
    {VK_FORMAT_A2B10G10R10_UINT_PACK32, "rgb10_a2ui"},
    {VK_FORMAT_R32G32_UINT, "rg32ui"},
    {VK_FORMAT_R16G16_UINT, "rg16ui"},
    {VK_FORMAT_R8G8_UINT, "rg8ui"},
    {VK_FORMAT_R16_UINT, "r16ui"},
    {VK_FORMAT_R8_UINT, "r8ui"},
    {VK_FORMAT_R64_UINT, "r64ui"},
    {VK_FORMAT_R64_SINT, "r64i"},
};

// One instruction's operands (the words after its opcode word).
struct Instruction {
    uint32_t opcode;
    const uint32_t* operands;
    uint32_t count;
};

class Module {
  public:
    explicit Module(const std::vector<uint32_t>& words) {
        if (words.size() < 5 || words[0] != kMagic) throw Error("not a SPIR-V module");
        for (size_t at = 5; at < words.size();) {
            const uint32_t wordCount = words[at] >> 16;
            if (wordCount == 0 || at + wordCount > words.size()) throw Error("truncated SPIR-V module");
            read({words[at] & 0xFFFFu, &words[at + 1], wordCount - 1});
            at += wordCount;
        }
    }

    std::vector<ShaderBinding> bindings() const {
        std::vector<ShaderBinding> result;
        for (const Variable& variable : variables_) {
            const auto binding = bindings_.find(variable.id);
            if (binding == bindings_.end()) continue;  // not a descriptor (inputs, outputs, push constants)
            ShaderBinding b;
            b.binding = binding->second;
            if (const auto set = sets_.find(variable.id); set != sets_.end()) b.set = set->second;
            b.name = nameOf(variable.id);
            const uint32_t type = elementType(pointee(variable.type));
            if (b.name.empty()) b.name = nameOf(type);  // an anonymous block instance: the block's name
            describe(variable.storageClass, type, b);
            result.push_back(b);
        }
        return result;
    }

  private:
    struct Variable {
        uint32_t id, type, storageClass;
    };
    struct Type {
        uint32_t opcode = 0;
        std::vector<uint32_t> operands;  // after the result id
    };

    void read(const Instruction& in) {
        const uint32_t* o = in.operands;
        switch (in.opcode) {
            case OpName:
                if (in.count >= 2)
                    names_[o[0]] =
                        std::string(reinterpret_cast<const char*>(o + 1), literalLength(o + 1, in.count - 1));
                break;
            case OpDecorate:
                if (in.count >= 3 && o[1] == Binding) bindings_[o[0]] = o[2];
                if (in.count >= 3 && o[1] == DescriptorSet) sets_[o[0]] = o[2];
                if (in.count >= 2 && (o[1] == Block || o[1] == BufferBlock)) blocks_[o[0]] = o[1];
                break;
            case OpVariable:
                if (in.count >= 3) variables_.push_back({o[1], o[0], o[2]});
                break;
            case OpTypeInt:
            case OpTypeFloat:
            case OpTypeImage:
            case OpTypeSampler:
            case OpTypeSampledImage:
            case OpTypeArray:
            case OpTypeRuntimeArray:
            case OpTypeStruct:
            case OpTypePointer:
                if (in.count >= 1) types_[o[0]] = {in.opcode, std::vector<uint32_t>(o + 1, o + in.count)};
                break;
            default:
                break;
        }
    }

    // A string literal's length within `words` words (it is nul-terminated and padded).
    static size_t literalLength(const uint32_t* words, size_t count) {
        const auto* chars = reinterpret_cast<const char*>(words);
        size_t n = 0;
        while (n < count * 4 && chars[n] != '\0') ++n;
        return n;
    }

    const Type& type(uint32_t id) const {
        const auto it = types_.find(id);
        if (it == types_.end())
            throw Error("SPIR-V: a descriptor's type %" + std::to_string(id) + " is not declared");
        return it->second;
    }
    std::string nameOf(uint32_t id) const {
        const auto it = names_.find(id);
        return it == names_.end() ? std::string() : it->second;
    }
    uint32_t pointee(uint32_t pointerType) const {
        const Type& t = type(pointerType);
        if (t.opcode != OpTypePointer || t.operands.size() < 2)
            throw Error("SPIR-V: a variable whose type is not a pointer");
        return t.operands[1];
    }
    // Arrays of descriptors describe as their element (vct binds none, but the type is still well defined).
    uint32_t elementType(uint32_t id) const {
        const Type* t = &type(id);
        while ((t->opcode == OpTypeArray || t->opcode == OpTypeRuntimeArray) && !t->operands.empty()) {
            id = t->operands[0];
            t = &type(id);
        }
        return id;
    }

    void describeImage(const Type& image, ShaderBinding& b) const {
        // OpTypeImage operands: sampled type, Dim, Depth, Arrayed, MS, Sampled, ImageFormat.
        if (image.operands.size() < 7) throw Error("SPIR-V: malformed OpTypeImage");
        const Type& sampled = type(image.operands[0]);
        b.texel = sampled.opcode == OpTypeFloat                                ? TexelClass::Float
                  : (sampled.operands.size() >= 2 && sampled.operands[1] != 0) ? TexelClass::Sint
                                                                               : TexelClass::Uint;
        const bool arrayed = image.operands[3] != 0;
        switch (image.operands[1]) {
            case Dim1D:
                b.dimension = arrayed ? VK_IMAGE_VIEW_TYPE_1D_ARRAY : VK_IMAGE_VIEW_TYPE_1D;
                break;
            case Dim2D:
                b.dimension = arrayed ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
                break;
            case Dim3D:
                b.dimension = VK_IMAGE_VIEW_TYPE_3D;
                break;
            case DimCube:
                b.dimension = arrayed ? VK_IMAGE_VIEW_TYPE_CUBE_ARRAY : VK_IMAGE_VIEW_TYPE_CUBE;
                break;
            default:
                break;
        }
        b.depthCompare = image.operands[2] == 1;
        const uint32_t format = image.operands[6];
        b.format = format < std::size(kImageFormats) ? kImageFormats[format].format : VK_FORMAT_UNDEFINED;
    }

    void describe(uint32_t storageClass, uint32_t typeId, ShaderBinding& b) const {
        const Type& t = type(typeId);
        if (storageClass == StorageBuffer) {
            b.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        } else if (storageClass == Uniform) {
            const auto block = blocks_.find(typeId);
            b.type = block != blocks_.end() && block->second == BufferBlock
                         ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                         : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        } else if (storageClass == UniformConstant && t.opcode == OpTypeSampler) {
            b.type = VK_DESCRIPTOR_TYPE_SAMPLER;
        } else if (storageClass == UniformConstant && t.opcode == OpTypeSampledImage && !t.operands.empty()) {
            b.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            describeImage(type(t.operands[0]), b);
        } else if (storageClass == UniformConstant && t.opcode == OpTypeImage) {
            describeImage(t, b);
            const uint32_t dim = t.operands[1], sampled = t.operands[5];
            if (dim == DimSubpassData)
                b.type = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
            else if (dim == DimBuffer)
                b.type = sampled == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER
                                      : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
            else
                b.type = sampled == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
        } else {
            throw Error("SPIR-V: binding " + std::to_string(b.binding) + " ('" + b.name +
                        "') is of a kind of descriptor vct does not bind");
        }
    }

    std::unordered_map<uint32_t, std::string> names_;
    std::unordered_map<uint32_t, uint32_t> bindings_, sets_, blocks_;
    std::unordered_map<uint32_t, Type> types_;
    std::vector<Variable> variables_;
};

}  // namespace

std::vector<ShaderBinding> reflectBindings(const std::vector<uint32_t>& spirv) {
    return Module(spirv).bindings();
}

std::string descriptorTypeName(VkDescriptorType type) {
    switch (type) {
        case VK_DESCRIPTOR_TYPE_SAMPLER:
            return "sampler";
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
            return "combined image sampler";
        case VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE:
            return "sampled image";
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
            return "storage image";
        case VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER:
            return "uniform texel buffer";
        case VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER:
            return "storage texel buffer";
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
            return "uniform buffer";
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
            return "storage buffer";
        case VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT:
            return "input attachment";
        default:
            return "descriptor type " + std::to_string(int(type));
    }
}

std::string glslFormatName(VkFormat format) {
    for (const FormatName& f : kImageFormats)
        if (f.format == format) return f.glsl;
    return "format " + std::to_string(int(format));
}

}  // namespace vct::vk
