#include "scene/builtin_scenes.h"

#include <filesystem>
#include <glm/gtc/constants.hpp>

#include "core/error.h"
#include "scene/builtin_hall.h"
#include "scene/gltf_loader.h"
#include "scene/procedural_textures.h"
#include "scene/scene_builder.h"

namespace vct {

namespace {

// A 4 m (x) × 3 m (y) × 4 m (z) closed room, floor at y = 0, centred on x = z = 0; see the description.
Scene cornell() {
    SceneBuilder b("cornell");
    const glm::vec3 white(0.725f, 0.71f, 0.68f), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.091f);

    Material floor = makeMaterial("floor", glm::vec3(0.75f), 1.0f, 1.0f);  // factors scale the stripe texture
    floor.metallicRoughnessTexture =
        b.texture(makeRoughnessStripes("floor roughness stripes", 256, 8, 0.05f, 0.8f, 0.0f));
    Material back = makeMaterial("back wall", white, 0.0f, 0.35f);
    back.normalTexture = b.texture(makeBumpNormalMap("back wall bumps", 512, 8, 0.8f));
    uint32_t floorMat = b.material(floor), backMat = b.material(back);
    uint32_t whiteMat = b.material(makeMaterial("white", white, 0.0f, 0.9f));
    uint32_t redMat = b.material(makeMaterial("red", red, 0.0f, 0.9f));
    uint32_t greenMat = b.material(makeMaterial("green", green, 0.0f, 0.9f));

    // Walls face inwards: the camera is inside, and single-sided quads keep back-face culling useful.
    const float W = 4.0f, H = 3.0f, D = 4.0f, x0 = -W / 2, x1 = W / 2, z0 = -D / 2, z1 = D / 2;
    Geometry floorG, ceilingG, backG, frontG, leftG, rightG;
    addQuad(floorG, {x0, 0, z1}, {W, 0, 0}, {0, 0, -D});  // stripes vary along x
    addQuad(ceilingG, {x0, H, z0}, {W, 0, 0}, {0, 0, D});
    addQuad(backG, {x0, 0, z0}, {W, 0, 0}, {0, H, 0}, {4.0f, 3.0f});  // 2048 × 1536 texels: 2 mm each
    addQuad(frontG, {x1, 0, z1}, {-W, 0, 0}, {0, H, 0});
    addQuad(leftG, {x0, 0, z1}, {0, 0, -D}, {0, H, 0});
    addQuad(rightG, {x1, 0, z0}, {0, 0, D}, {0, H, 0});
    Node room;
    room.name = "room";
    room.mesh = b.mesh("room", {{floorG, floorMat},
                                {ceilingG, whiteMat},
                                {backG, backMat},
                                {frontG, whiteMat},
                                {leftG, redMat},
                                {rightG, greenMat}});
    b.node(room);

    Node ball;
    ball.name = "gold sphere";
    ball.translation = glm::vec3(-1.0f, 0.5f, -0.8f);
    ball.mesh = b.mesh("sphere", {{sphere(0.5f, 64, 32),
                                   b.material(makeMaterial("gold", {1.0f, 0.766f, 0.336f}, 1.0f, 0.2f))}});
    b.node(ball);

    Node tall;
    tall.name = "tall box";
    tall.translation = glm::vec3(0.9f, 0.9f, -0.9f);
    tall.rotation = glm::angleAxis(glm::radians(20.0f), glm::vec3(0, 1, 0));
    tall.mesh = b.mesh("tall box", {{box({0.4f, 0.9f, 0.4f}), whiteMat}});
    b.node(tall);

    // A small cube circling in front of the objects (radius 0.7 m around (0, 0.35, 0.4), one turn in 4 s,
    // counter-clockwise seen from above) while spinning about +Y once per loop.
    Node cube;
    cube.name = "moving cube";
    cube.mesh = b.mesh(
        "cube", {{box(glm::vec3(0.15f)), b.material(makeMaterial("blue", {0.2f, 0.4f, 0.9f}, 0.0f, 0.5f))}});
    int cubeNode = b.node(cube);
    AnimationChannel move{cubeNode, AnimationPath::Translation, Interpolation::Linear, {}, {}};
    const int keys = 32;  // 11.25° segments: the linear path stays within 4 mm of the circle
    for (int k = 0; k <= keys; ++k) {
        float t = 4.0f * float(k) / keys, a = glm::two_pi<float>() * float(k) / keys;
        move.times.push_back(t);
        move.values.emplace_back(0.7f * std::cos(a), 0.35f, 0.4f - 0.7f * std::sin(a), 0.0f);
    }
    AnimationChannel spin{cubeNode, AnimationPath::Rotation, Interpolation::Linear, {}, {}};
    for (int k = 0; k <= 4; ++k) {  // quarter turns; slerp fills in between
        glm::quat q = glm::angleAxis(glm::half_pi<float>() * float(k), glm::vec3(0, 1, 0));
        spin.times.push_back(float(k));
        spin.values.emplace_back(q.x, q.y, q.z, q.w);
    }
    b.scene.animations.push_back(Animation{"cube orbit", {move, spin}, 4.0f});

    // Spot light 10 cm under the ceiling, 0.5 m towards the back, pointing straight down. 40 cd gives
    // E = 40 / 2.9² ≈ 4.8 lux on the floor below it, i.e. radiance ≈ 0.75·4.8/π ≈ 1.1 from the floor:
    // well exposed at exposure 1 with Reinhard/ACES, with the walls' lower halves lit at grazing angles
    // (which shows the back wall's bumps) and the rest lit indirectly.
    Light spot;
    spot.name = "spot light";
    spot.type = LightType::Spot;
    spot.color = glm::vec3(1.0f, 0.96f, 0.9f);
    spot.intensity = 40.0f;
    spot.innerConeAngle = 0.6f;
    spot.outerConeAngle = 0.9f;
    b.lightNode(spot, {0.0f, 2.9f, -0.5f}, glm::angleAxis(-glm::half_pi<float>(), glm::vec3(1, 0, 0)));

    b.cameraNode("camera", {0.0f, 2.0f, 1.9f}, {0.0f, 0.75f, -1.2f}, 55.0f, 20.0f);
    b.scene.validate();
    return std::move(b.scene);
}

// A 10 m × 10 m silver plane (y = 0) with a 512² bump normal map repeated once per metre (2 mm texels,
// 8-texel period), lit by a directional light placed so its mirror highlight is in the middle of the view.
Scene plane() {
    SceneBuilder b("plane");
    Material m = makeMaterial("bumpy silver", glm::vec3(0.95f), 1.0f, 0.15f);
    m.normalTexture = b.texture(makeBumpNormalMap("plane bumps", 512, 8, 0.8f));
    Geometry g;
    addQuad(g, {-5.0f, 0.0f, 5.0f}, {10.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -10.0f}, glm::vec2(10.0f));
    Node n;
    n.name = "plane";
    n.mesh = b.mesh("plane", {{g, b.material(m)}});
    b.node(n);

    const glm::vec3 eye(0.0f, 1.5f, 3.0f);
    b.cameraNode("camera", eye, glm::vec3(0.0f), 45.0f, 50.0f);
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.intensity = 3.0f;
    // The light travels along the mirror image of the view ray through the origin: (0, -1.5, 3).
    glm::vec3 dir = glm::normalize(glm::vec3(0.0f, -eye.y, eye.z));
    b.lightNode(sun, -dir * 5.0f, glm::quatLookAtRH(dir, glm::vec3(0, 1, 0)));
    b.scene.validate();
    return std::move(b.scene);
}

// An open courtyard under the sky (issue 20): an 8 m × 8 m grey floor, two walls meeting at a corner, a white
// box and a gold sphere, lit by a sun at 40° elevation: most of its light after the sun's comes from the sky
// (docs/design.md §5.9), so it is the open scene of benchmarks/truth.sh.
Scene courtyard() {
    SceneBuilder b("courtyard");
    const uint32_t grey = b.material(makeMaterial("grey", glm::vec3(0.5f), 0.0f, 0.9f));
    const uint32_t brick = b.material(makeMaterial("brick", {0.6f, 0.25f, 0.15f}, 0.0f, 0.8f));
    const uint32_t white = b.material(makeMaterial("white", glm::vec3(0.8f), 0.0f, 0.6f));
    const uint32_t gold = b.material(makeMaterial("gold", {1.0f, 0.78f, 0.34f}, 1.0f, 0.3f));
    Geometry floorG, backG, leftG;
    addQuad(floorG, {-4.0f, 0.0f, 4.0f}, {8.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -8.0f});
    addQuad(backG, {-4.0f, 0.0f, -4.0f}, {8.0f, 0.0f, 0.0f}, {0.0f, 2.5f, 0.0f});
    addQuad(leftG, {-4.0f, 0.0f, 4.0f}, {0.0f, 0.0f, -8.0f}, {0.0f, 2.5f, 0.0f});
    Node ground;
    ground.name = "courtyard";
    ground.mesh = b.mesh("courtyard", {{floorG, grey}, {backG, brick}, {leftG, brick}});
    b.node(ground);
    Node block;
    block.name = "box";
    block.translation = {-1.2f, 0.75f, -1.5f};
    block.rotation = glm::angleAxis(glm::radians(25.0f), glm::vec3(0, 1, 0));
    block.mesh = b.mesh("box", {{box({0.75f, 0.75f, 0.75f}), white}});
    b.node(block);
    Node ball;
    ball.name = "sphere";
    ball.translation = {1.0f, 0.6f, 0.0f};
    ball.mesh = b.mesh("sphere", {{sphere(0.6f, 32, 16), gold}});
    b.node(ball);
    b.cameraNode("camera", {3.5f, 2.2f, 4.5f}, {-0.5f, 0.6f, -1.0f}, 50.0f, 50.0f);
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.intensity = 3.0f;
    const glm::vec3 dir = -glm::normalize(glm::vec3(0.55f, std::tan(glm::radians(40.0f)), 0.83f));
    b.lightNode(sun, -dir * 6.0f, glm::quatLookAtRH(dir, glm::vec3(0, 1, 0)));
    b.scene.validate();
    return std::move(b.scene);
}

// cornell turned 30° about y, camera and light with it: the same room off the grid's axes, whose walls are staircases of
// voxels that the closure box does not close; the static grid's closed regions do (docs/design.md §5.6). The truth is
// cornell's, turned: what the room renders should not depend on how it stands in the grid.
Scene cornellTurned() {
    Scene scene = cornell();
    scene.name = "cornell-turned";
    Node turn;
    turn.name = "turn";
    turn.rotation = glm::angleAxis(glm::radians(30.0f), glm::vec3(0, 1, 0));
    turn.children = scene.roots;
    const int index = int(scene.nodes.size());
    for (int root : scene.roots) scene.nodes[size_t(root)].parent = index;
    scene.nodes.push_back(turn);
    scene.roots = {index};
    scene.validate();
    return scene;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
    return {"cornell", "plane", "courtyard", "hall", "cornell-turned"};
}

std::string builtinSceneDescription(const std::string& name) {
    if (name == "cornell")
        return "4x3x4 m closed room: red/green side walls, glossy floor with 8 roughness stripes (0.05-0.8), "
               "bump-normal-mapped back wall, gold sphere, tall white box, a blue cube circling the floor "
               "(4 s loop), one 40 cd spot light under the ceiling";
    if (name == "plane")
        return "10x10 m silver plane (roughness 0.15) with a fine bump normal map, a directional light and "
               "an "
               "oblique camera on its highlight (normal-map filtering tests)";
    if (name == "hall")
        return "40x10x16 m hall: two colonnades of 9 columns with arches, thin (0.1 m) partition walls with "
               "doorways in the aisles, a sun through three roof openings, a bronze sphere, an orange cube "
               "travelling down the nave (8 s loop); for speed at large sizes";
    if (name == "cornell-turned")
        return "cornell turned 30 deg about y, camera and light with it: a closed room off the voxel grid's "
               "axes "
               "(closed regions, docs/design.md sec. 5.6)";
    if (name == "courtyard")
        return "8x8 m open courtyard: grey floor, two brick walls, a white box and a gold sphere under a sun "
               "at "
               "40 deg and the procedural sky (environment tests, the open scene of the truth runs)";
    return "";
}

std::optional<Scene> makeBuiltinScene(const std::string& name) {
    if (name == "cornell") return cornell();
    if (name == "plane") return plane();
    if (name == "hall") return hallScene();
    if (name == "courtyard") return courtyard();
    if (name == "cornell-turned") return cornellTurned();
    return std::nullopt;
}

Scene loadScene(const std::string& nameOrPath) {
    if (auto scene = makeBuiltinScene(nameOrPath)) return std::move(*scene);
    std::error_code ec;
    if (!std::filesystem::exists(nameOrPath, ec))
        throw Error("unknown scene '" + nameOrPath + "' (not a built-in scene and no such file)");
    return loadGltf(nameOrPath);
}

}  // namespace vct
