#include "scene/builtin_hall.h"

#include <glm/gtc/constants.hpp>

#include "scene/scene_builder.h"

namespace vct {

namespace {

// The hall's dimensions (m): x along its length, y up, z across; floor at y = 0, centred on x = z = 0.
constexpr float kLength = 40.0f, kHeight = 10.0f, kWidth = 16.0f;
constexpr float kShell = 0.3f;      // outer walls and roof: boxes, so they cast shadows from either side
constexpr float kPartition = 0.1f;  // the aisles' partition walls: thinner than a voxel even at 256³ (0.16 m)
constexpr float kSkylight = 4.0f;   // square openings in the roof, centred at x = -12, 0, 12 on z = 0
constexpr float kColumnRadius = 0.35f, kColumnHeight = 6.0f, kBay = 4.0f, kColonnadeZ = 4.0f;

// The roof slab with three square skylights, as boxes around the openings.
void addRoof(Geometry& g) {
    const float y = kHeight + 0.5f * kShell, hx = 0.5f * kLength, hz = 0.5f * kWidth, hs = 0.5f * kSkylight;
    const float strip = 0.5f * (hz - hs);  // the two full-length strips beside the openings
    addBox(g, {0.0f, y, -hz + strip}, {hx, 0.5f * kShell, strip});
    addBox(g, {0.0f, y, hz - strip}, {hx, 0.5f * kShell, strip});
    // Between and beyond the openings at x = -12, 0, 12, along the middle band.
    const float edges[] = {-hx, -12.0f - hs, -12.0f + hs, -hs, hs, 12.0f - hs, 12.0f + hs, hx};
    for (int i = 0; i < 8; i += 2) {
        const float x0 = edges[i], x1 = edges[i + 1];
        addBox(g, {0.5f * (x0 + x1), y, 0.0f}, {0.5f * (x1 - x0), 0.5f * kShell, hs});
    }
}

// A thin wall across an aisle at x, from z0 to z1, with a 1.2 m × 2.2 m doorway in the middle.
void addPartition(Geometry& g, float x, float z0, float z1) {
    const float door = 1.2f, doorHeight = 2.2f, height = kColumnHeight, zm = 0.5f * (z0 + z1);
    const float t = 0.5f * kPartition;
    const float side = 0.5f * (z1 - z0 - door);
    addBox(g, {x, 0.5f * height, z0 + 0.5f * side}, {t, 0.5f * height, 0.5f * side});
    addBox(g, {x, 0.5f * height, z1 - 0.5f * side}, {t, 0.5f * height, 0.5f * side});
    addBox(g, {x, 0.5f * (doorHeight + height), zm}, {t, 0.5f * (height - doorHeight), 0.5f * door});
}

// A row of columns along x at z, each bay spanned by a semicircular arch and a beam over the arches.
void addColonnade(Geometry& columns, Geometry& arches, float z) {
    const float first = -0.5f * kLength + kBay;
    const int count = int((kLength - 2.0f * kBay) / kBay) + 1;  // 9 columns, 8 bays
    for (int i = 0; i < count; ++i)
        addCylinder(columns, {first + float(i) * kBay, 0.0f, z}, kColumnRadius, kColumnHeight, 24);
    const float depth = 2.0f * kColumnRadius, inner = 0.5f * kBay - kColumnRadius, outer = 0.5f * kBay;
    for (int i = 0; i + 1 < count; ++i)
        addArch(arches, {first + (float(i) + 0.5f) * kBay, kColumnHeight, z}, inner, outer, depth, 16);
    const float beamY = kColumnHeight + outer + 0.2f;
    addBox(arches, {0.0f, beamY, z}, {0.5f * float(count - 1) * kBay, 0.2f, 0.5f * depth});
}

}  // namespace

Scene hallScene() {
    SceneBuilder b("hall");
    const uint32_t stone = b.material(makeMaterial("stone floor", {0.55f, 0.5f, 0.45f}, 0.0f, 0.6f));
    const uint32_t plaster = b.material(makeMaterial("plaster", {0.8f, 0.78f, 0.74f}, 0.0f, 0.9f));
    const uint32_t red = b.material(makeMaterial("red end wall", {0.63f, 0.1f, 0.07f}, 0.0f, 0.9f));
    const uint32_t blue = b.material(makeMaterial("blue end wall", {0.1f, 0.2f, 0.6f}, 0.0f, 0.9f));
    const uint32_t marble = b.material(makeMaterial("marble", {0.85f, 0.83f, 0.8f}, 0.0f, 0.3f));
    const uint32_t bronze = b.material(makeMaterial("bronze", {0.8f, 0.5f, 0.25f}, 1.0f, 0.35f));

    const float hx = 0.5f * kLength, hz = 0.5f * kWidth, hy = 0.5f * kHeight, s = 0.5f * kShell;
    Geometry floor, shell, redWall, blueWall, roof, partitions, columns, arches;
    addBox(floor, {0.0f, -s, 0.0f}, {hx + kShell, s, hz + kShell});
    addBox(shell, {0.0f, hy, -hz - s}, {hx + kShell, hy, s});  // the long walls, outside the floor's extent
    addBox(shell, {0.0f, hy, hz + s}, {hx + kShell, hy, s});
    addBox(redWall, {-hx - s, hy, 0.0f}, {s, hy, hz});
    addBox(blueWall, {hx + s, hy, 0.0f}, {s, hy, hz});
    addRoof(roof);
    for (float x : {-8.0f, 0.0f, 8.0f}) {
        addPartition(partitions, x, -hz, -kColonnadeZ - kColumnRadius);
        addPartition(partitions, x, kColonnadeZ + kColumnRadius, hz);
    }
    addColonnade(columns, arches, -kColonnadeZ);
    addColonnade(columns, arches, kColonnadeZ);

    Node hall;
    hall.name = "hall";
    hall.mesh = b.mesh("hall", {{floor, stone},
                                {shell, plaster},
                                {redWall, red},
                                {blueWall, blue},
                                {roof, plaster},
                                {partitions, plaster},
                                {columns, marble},
                                {arches, marble}});
    b.node(hall);

    Node statue;
    statue.name = "bronze sphere";
    statue.translation = glm::vec3(6.0f, 1.0f, 0.0f);
    statue.mesh = b.mesh("sphere", {{sphere(1.0f, 48, 24), bronze}});
    b.node(statue);

    // The moving object: a 1.5 m cube travelling 24 m down the nave and back (8 s loop), turning as it goes.
    Node cart;
    cart.name = "moving cube";
    cart.mesh = b.mesh("cube", {{box(glm::vec3(0.75f)),
                                 b.material(makeMaterial("orange", {0.9f, 0.45f, 0.1f}, 0.0f, 0.5f))}});
    const int cartNode = b.node(cart);
    AnimationChannel move{cartNode, AnimationPath::Translation, Interpolation::Linear, {}, {}};
    move.times = {0.0f, 4.0f, 8.0f};
    move.values = {{-12.0f, 0.75f, -1.5f, 0.0f}, {12.0f, 0.75f, -1.5f, 0.0f}, {-12.0f, 0.75f, -1.5f, 0.0f}};
    AnimationChannel spin{cartNode, AnimationPath::Rotation, Interpolation::Linear, {}, {}};
    for (int k = 0; k <= 8; ++k) {  // quarter turns per second; slerp fills in between
        const glm::quat q = glm::angleAxis(glm::half_pi<float>() * float(k), glm::vec3(0, 1, 0));
        spin.times.push_back(float(k));
        spin.values.emplace_back(q.x, q.y, q.z, q.w);
    }
    b.scene.animations.push_back(Animation{"cube down the nave", {move, spin}, 8.0f});

    // The sun, 58° above the horizon, through the skylights: 10 lux gives the lit floor patches a radiance of
    // about 0.5 · 10 · 0.85 / π ≈ 1.4, well exposed at exposure 1; everything else is lit by bounced light.
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.color = glm::vec3(1.0f, 0.95f, 0.85f);
    sun.intensity = 10.0f;
    const glm::vec3 dir = glm::normalize(glm::vec3(0.35f, -0.85f, 0.4f));  // the way the light travels
    b.lightNode(sun, -dir * 20.0f, glm::quatLookAtRH(dir, glm::vec3(0, 1, 0)));

    b.cameraNode("camera", {-18.0f, 1.7f, 0.5f}, {10.0f, 3.0f, -0.5f}, 60.0f, 100.0f);
    b.scene.validate();
    return std::move(b.scene);
}

}  // namespace vct
