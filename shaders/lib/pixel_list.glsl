// An entry of the compacted pixel lists (shared.h's ResampleListHeader and its entries: the resample pass's list
// of pixels to re-trace, the direct pass's of pixels to shade): x | y << 16, for images up to 65535 pixels a side.
// Written by upsample.comp and direct_select.comp, read by resample.comp and direct.comp. GLSL only.
#ifndef VCT_PIXEL_LIST_GLSL
#define VCT_PIXEL_LIST_GLSL

uint packListedPixel(ivec2 pixel) { return uint(pixel.x) | (uint(pixel.y) << 16); }
ivec2 unpackListedPixel(uint entry) { return ivec2(entry & 0xffffu, entry >> 16); }

// Appends `pixel` to `list` (a buffer block's instance name: a ResampleListHeader `header`, then `pixels[]`) and
// counts its reader's indirect dispatch up by one workgroup for every `groupSize` entries. A macro because a GLSL
// function cannot take a buffer block.
#define APPEND_LISTED_PIXEL(list, pixel, groupSize)                                     \
    {                                                                                   \
        const uint listedIndex = atomicAdd(list.header.counts.x, 1u);                   \
        list.pixels[listedIndex] = packListedPixel(pixel);                              \
        if (listedIndex % uint(groupSize) == 0u) atomicAdd(list.header.dispatch.x, 1u); \
    }

#endif  // VCT_PIXEL_LIST_GLSL
