// lesson_04/peers.wgsl: the point-shadow lookups of renderers people use
// (lesson_04::peers::Peer). Appended after cube_map.wgsl.

// ANCHOR: learnopengl_disk
// LearnOpenGL's soft point shadows (3.2.2.point_shadows.fs): 20 taps along
// the cube's corner and edge directions, in its order, on a disk that
// widens with the viewer's distance, in world units; the cube holds
// distance / far_plane.
const GRID_SAMPLING_DISK = array<vec3<f32>, 20>(
    vec3<f32>(1.0, 1.0, 1.0), vec3<f32>(1.0, -1.0, 1.0), vec3<f32>(-1.0, -1.0, 1.0), vec3<f32>(-1.0, 1.0, 1.0),
    vec3<f32>(1.0, 1.0, -1.0), vec3<f32>(1.0, -1.0, -1.0), vec3<f32>(-1.0, -1.0, -1.0), vec3<f32>(-1.0, 1.0, -1.0),
    vec3<f32>(1.0, 1.0, 0.0), vec3<f32>(1.0, -1.0, 0.0), vec3<f32>(-1.0, -1.0, 0.0), vec3<f32>(-1.0, 1.0, 0.0),
    vec3<f32>(1.0, 0.0, 1.0), vec3<f32>(-1.0, 0.0, 1.0), vec3<f32>(1.0, 0.0, -1.0), vec3<f32>(-1.0, 0.0, -1.0),
    vec3<f32>(0.0, 1.0, 1.0), vec3<f32>(0.0, -1.0, 1.0), vec3<f32>(0.0, -1.0, -1.0), vec3<f32>(0.0, 1.0, -1.0),
);

fn learnopengl_disk(world: vec3<f32>) -> f32 {
    let v = world - light.position_or_dir.xyz;
    let view_distance = length(camera.eye.xyz - world);
    let disk = (1.0 + view_distance / cube_far()) * params.peer_scale;
    // `currentDepth - bias > closestDepth` is shadow: compare d − bias.
    let z = receiver_depth(v, length(v) - params.bias_world);
    var lit = 0.0;
    for (var i = 0; i < 20; i++) {
        let dir = v + GRID_SAMPLING_DISK[i] * disk;
        lit += textureSampleCompareLevel(cube_map, cube_compare, dir, z);
    }
    return lit / 20.0;
}
// ANCHOR_END: learnopengl_disk

// ANCHOR: bevy_point
// Bevy's D3D 8×MSAA sample positions and their Gaussian weights
// (shadow_sampling.wgsl).
const D3D_POSITIONS = array<vec2<f32>, 8>(
    vec2<f32>(0.125, -0.375), vec2<f32>(-0.125, 0.375), vec2<f32>(0.625, 0.125), vec2<f32>(-0.375, -0.625),
    vec2<f32>(-0.625, 0.625), vec2<f32>(-0.875, -0.125), vec2<f32>(0.375, 0.875), vec2<f32>(0.875, -0.875),
);
const D3D_COEFFS = array<f32, 8>(0.157112, 0.157112, 0.138651, 0.130251, 0.114946, 0.114946, 0.107982, 0.079001);
const POINT_SHADOW_SCALE: f32 = 0.003;

// Bevy's fetch_point_shadow: offsets along the normal (scaled with the
// major-axis distance, like the texels) and towards the light, then the
// hardware depth of the moved point, filtered by a Gaussian on 8 taps.
fn bevy_point(world: vec3<f32>, n: vec3<f32>) -> f32 {
    let to_light = light.position_or_dir.xyz - world;
    let a = abs(to_light);
    let major = max(a.x, max(a.y, a.z));
    let moved = world + params.peer_scale * major * n + params.bias_world * normalize(to_light);
    let v = moved - light.position_or_dir.xyz;
    let z = receiver_depth(v, length(v));
    // Bevy samples its cube at v with z flipped ("cubemaps assume a
    // left-handed coordinate space") and lays its taps out in a basis of
    // that flipped direction (its orthonormalize); flipping each tap back
    // puts it where Bevy's lies, in this lesson's cube.
    let flip_z = vec3<f32>(1.0, 1.0, -1.0);
    let local = v * flip_z;
    var up = vec3<f32>(0.0, 1.0, 0.0);
    if dot(up, normalize(local)) > 0.99 {
        up = vec3<f32>(1.0, 0.0, 0.0);
    }
    let bz = normalize(local);
    let bx = normalize(cross(bz, up));
    let by = cross(bz, bx);
    let scale = POINT_SHADOW_SCALE * major;
    var lit = 0.0;
    for (var i = 0; i < 8; i++) {
        let o = D3D_POSITIONS[i] * scale;
        let dir = (local + o.x * bx + o.y * by) * flip_z;
        lit += D3D_COEFFS[i] * textureSampleCompareLevel(cube_map, cube_compare, dir, z);
    }
    return lit;
}
// ANCHOR_END: bevy_point
