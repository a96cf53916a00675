// Scene, shadow and background passes of the scenethesis renderer.
//
// Targets: 0 = sRGB colour, 1 = linear depth along the optical axis (f32 bits in an R32Uint),
// 2 = instance index (0 = nothing).

struct Globals {
    clip_from_world: mat4x4<f32>,
    light_from_world: mat4x4<f32>,
    // Third row of the camera-from-world matrix: depth = -dot(view_z, (p, 1)).
    view_z: vec4<f32>,
    // xyz: unit direction toward the light; w: shadow-map texel size in metres.
    light_dir: vec4<f32>,
    // rgb: sun radiance; w: 1 when shadows are on.
    sun: vec4<f32>,
    sky_ambient: vec4<f32>,
    ground_ambient: vec4<f32>,
    // Columns of the world-from-camera rotation.
    cam_right: vec4<f32>,
    cam_up: vec4<f32>,
    cam_back: vec4<f32>,
    // fx, fy, cx, cy in pixels.
    intrinsics: vec4<f32>,
    bg_top: vec4<f32>,
    bg_horizon: vec4<f32>,
    bg_bottom: vec4<f32>,
};

@group(0) @binding(0) var<uniform> g: Globals;
@group(1) @binding(0) var shadow_map: texture_depth_2d;
@group(1) @binding(1) var shadow_sampler: sampler_comparison;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
    @location(3) instance: u32,
};

struct Varying {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
    @location(3) @interpolate(flat) instance: u32,
    @location(4) depth: f32,
};

struct Targets {
    @location(0) color: vec4<f32>,
    @location(1) depth: u32,
    @location(2) instance: u32,
};

@vertex
fn vs_scene(v: VertexIn) -> Varying {
    var out: Varying;
    let p = vec4<f32>(v.position, 1.0);
    out.clip = g.clip_from_world * p;
    out.world = v.position;
    out.normal = v.normal;
    out.albedo = v.albedo;
    out.instance = v.instance;
    out.depth = -dot(g.view_z, p);
    return out;
}

// Fraction of sunlight reaching `world` (1 = lit), from a 4×4 percentage-closer filter over
// the shadow map with hardware bilinear comparison: soft edges a few centimetres wide.
fn sunlight(world: vec3<f32>, normal: vec3<f32>) -> f32 {
    if g.sun.w < 0.5 {
        return 1.0;
    }
    let texel = g.light_dir.w;
    let offset_world = world + normal * (1.5 * texel);
    let p = g.light_from_world * vec4<f32>(offset_world, 1.0);
    let uv = vec2<f32>(p.x * 0.5 + 0.5, 0.5 - p.y * 0.5);
    if uv.x <= 0.0 || uv.x >= 1.0 || uv.y <= 0.0 || uv.y >= 1.0 {
        return 1.0;
    }
    let size = vec2<f32>(textureDimensions(shadow_map));
    // Receivers beyond the casters' sphere (a floor far below) compare as farthest: in shadow
    // wherever any caster covers their texel.
    let reference = min(p.z, 1.0) - 0.0005;
    var lit = 0.0;
    for (var i = 0; i < 4; i++) {
        for (var j = 0; j < 4; j++) {
            let o = (vec2<f32>(f32(i), f32(j)) - 1.5) * 1.25 / size;
            lit += textureSampleCompareLevel(shadow_map, shadow_sampler, uv + o, reference);
        }
    }
    return lit / 16.0;
}

@fragment
fn fs_scene(in: Varying) -> Targets {
    let n = normalize(in.normal);
    let l = g.light_dir.xyz;
    let direct = max(dot(n, l), 0.0);
    var shadow = 1.0;
    if direct > 0.0 {
        shadow = sunlight(in.world, n);
    }
    let ambient = mix(g.ground_ambient.rgb, g.sky_ambient.rgb, n.y * 0.5 + 0.5);
    let light = ambient + g.sun.rgb * (direct * shadow);
    var out: Targets;
    out.color = vec4<f32>(clamp(in.albedo * light, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
    out.depth = bitcast<u32>(in.depth);
    out.instance = in.instance;
    return out;
}

@vertex
fn vs_shadow(v: VertexIn) -> @builtin(position) vec4<f32> {
    return g.light_from_world * vec4<f32>(v.position, 1.0);
}

@vertex
fn vs_background(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    // One triangle covering the whole viewport.
    let x = f32(i32(index & 1u) * 4 - 1);
    let y = f32(i32(index >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_background(@builtin(position) frag: vec4<f32>) -> Targets {
    let k = g.intrinsics;
    let c = vec3<f32>((frag.x - k.z) / k.x, -(frag.y - k.w) / k.y, -1.0);
    let dir = normalize(g.cam_right.xyz * c.x + g.cam_up.xyz * c.y + g.cam_back.xyz * c.z);
    var color: vec3<f32>;
    if dir.y >= 0.0 {
        color = mix(g.bg_horizon.rgb, g.bg_top.rgb, pow(dir.y, 0.5));
    } else {
        color = mix(g.bg_horizon.rgb, g.bg_bottom.rgb, pow(-dir.y, 0.5));
    }
    var out: Targets;
    out.color = vec4<f32>(color, 1.0);
    out.depth = 0u;
    out.instance = 0u;
    return out;
}
