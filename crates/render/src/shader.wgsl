// Scene, shadow, background and ambient-occlusion passes of the scenethesis renderer.
//
// Scene-pass targets: 0 = sRGB lit colour (alpha: the share of the light that is ambient),
// 1 = linear depth along the optical axis (f32 bits in an R32Uint), 2 = instance index
// (0 = nothing). The ambient-occlusion pass reads 0 and 1 and writes the final colour.

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
    // xyz: the camera's position.
    eye: vec4<f32>,
    // x: search radius in metres; y: strength (0 = off); z: widest radius in pixels;
    // w: supersampling factor (scene-pass pixels per output pixel and side).
    occlusion: vec4<f32>,
};

@group(0) @binding(0) var<uniform> g: Globals;
@group(1) @binding(0) var shadow_map: texture_depth_2d;
@group(1) @binding(1) var shadow_sampler: sampler_comparison;
// rgb: the share of sunlight the see-through casters (glass) let through, per channel; a: the
// nearest one's depth from the sun. Cleared to 1 (no glass: all light, farthest).
@group(1) @binding(2) var shadow_tint: texture_2d<f32>;
@group(1) @binding(3) var tint_sampler: sampler;
// One layer per library material: sRGB albedo multiplier, tangent-space normal (+Y toward the
// image's top), metallic-roughness (G roughness, B metalness).
@group(2) @binding(0) var base_maps: texture_2d_array<f32>;
@group(2) @binding(1) var normal_maps: texture_2d_array<f32>;
@group(2) @binding(2) var mr_maps: texture_2d_array<f32>;
@group(2) @binding(3) var map_sampler: sampler;

const PI: f32 = 3.14159265;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    // rgb: linear albedo (the factor of the base-colour map when textured); a: opacity.
    @location(2) albedo: vec4<f32>,
    @location(3) instance: u32,
    @location(4) uv: vec2<f32>,
    @location(5) tangent: vec4<f32>,
    @location(6) roughness_metallic: vec2<f32>,
    // 1 + the material's layer in the map arrays; 0 for a plain colour.
    @location(7) layer: u32,
};

struct Varying {
    // Invariant: the depth pre-pass and the scene pass compute the same depths.
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec4<f32>,
    @location(3) @interpolate(flat) instance: u32,
    @location(4) depth: f32,
    @location(5) uv: vec2<f32>,
    @location(6) tangent: vec4<f32>,
    @location(7) roughness_metallic: vec2<f32>,
    @location(8) @interpolate(flat) layer: u32,
};

struct Targets {
    @location(0) color: vec4<f32>,
    @location(1) depth: u32,
    @location(2) instance: u32,
};

// Where a vertex goes when its pass does not draw its surface: outside the clip volume, so
// its whole triangle (one surface, one opacity) is culled before any fragment is shaded.
const CULLED: vec4<f32> = vec4<f32>(2.0, 2.0, 2.0, 1.0);

// The opaque pass: see-through surfaces are culled (rather than discarded per fragment, which
// would cost software rasterizers their early depth test).
@vertex
fn vs_scene(v: VertexIn) -> Varying {
    var out = scene_vertex(v);
    if v.albedo.a < 0.999 {
        out.clip = CULLED;
    }
    return out;
}

// The depth pre-pass: the opaque surfaces' depth, so that the scene pass shades each pixel
// once (its depth test is `LessEqual` against this) however many surfaces overlap there.
@vertex
fn vs_prepass(v: VertexIn) -> @builtin(position) @invariant vec4<f32> {
    if v.albedo.a < 0.999 {
        return CULLED;
    }
    return g.clip_from_world * vec4<f32>(v.position, 1.0);
}

// The pre-pass writes no colour (its targets' write masks are empty).
@fragment
fn fs_prepass() -> Targets {
    var out: Targets;
    return out;
}

// The glass pass: only see-through surfaces.
@vertex
fn vs_glass(v: VertexIn) -> Varying {
    var out = scene_vertex(v);
    if v.albedo.a >= 0.999 {
        out.clip = CULLED;
    }
    return out;
}

fn scene_vertex(v: VertexIn) -> Varying {
    var out: Varying;
    let p = vec4<f32>(v.position, 1.0);
    out.clip = g.clip_from_world * p;
    out.world = v.position;
    out.normal = v.normal;
    out.albedo = v.albedo;
    out.instance = v.instance;
    out.depth = -dot(g.view_z, p);
    out.uv = v.uv;
    out.tangent = v.tangent;
    out.roughness_metallic = v.roughness_metallic;
    out.layer = v.layer;
    return out;
}

// Share of sunlight reaching `world` per channel (1 = lit): the opaque casters' shadow, from a
// 4×4 percentage-closer filter over the shadow map with hardware bilinear comparison (soft
// edges a few centimetres wide), times the colour the glass between it and the sun lets through.
fn sunlight(world: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    if g.sun.w < 0.5 {
        return vec3<f32>(1.0);
    }
    let texel = g.light_dir.w;
    let offset_world = world + normal * (1.5 * texel);
    let p = g.light_from_world * vec4<f32>(offset_world, 1.0);
    let uv = vec2<f32>(p.x * 0.5 + 0.5, 0.5 - p.y * 0.5);
    if uv.x <= 0.0 || uv.x >= 1.0 || uv.y <= 0.0 || uv.y >= 1.0 {
        return vec3<f32>(1.0);
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
    return lit / 16.0 * glass_transmission(uv, reference, texel * size.x);
}

// The light the glass at shadow-map position `uv` lets through to a receiver at sun depth
// `reference`: its tint when the receiver lies at least 2 cm beyond the nearest pane (depth
// spans `depth_span` metres), else all of it (the pane itself, or what stands on it).
fn glass_transmission(uv: vec2<f32>, reference: f32, depth_span: f32) -> vec3<f32> {
    let tint = textureSampleLevel(shadow_tint, tint_sampler, uv, 0.0);
    if reference > tint.a + 0.02 / depth_span {
        return tint.rgb;
    }
    return vec3<f32>(1.0);
}

// A surface point as the lights see it: albedo, shading normal, roughness, metalness.
struct SurfacePoint {
    albedo: vec3<f32>,
    normal: vec3<f32>,
    roughness: f32,
    metallic: f32,
};

// The surface at a fragment: its maps (when it wears a library material) multiplying its
// factors, the normal map bent into the world through the interpolated tangent frame. The
// maps are sampled for every fragment (sampling needs uniform control flow) and ignored for
// plain colours.
fn surface_point(in: Varying, front: bool) -> SurfacePoint {
    var n = normalize(in.normal);
    if !front {
        n = -n;
    }
    let layer = i32(max(in.layer, 1u)) - 1;
    let base = textureSample(base_maps, map_sampler, in.uv, layer).rgb;
    let bump = textureSample(normal_maps, map_sampler, in.uv, layer).xyz * 2.0 - 1.0;
    let mr = textureSample(mr_maps, map_sampler, in.uv, layer);
    var p: SurfacePoint;
    p.albedo = in.albedo.rgb;
    p.normal = n;
    p.roughness = in.roughness_metallic.x;
    p.metallic = in.roughness_metallic.y;
    if in.layer > 0u {
        p.albedo = in.albedo.rgb * base;
        let t = normalize(in.tangent.xyz - n * dot(n, in.tangent.xyz));
        let b = cross(n, t) * in.tangent.w;
        p.normal = normalize(t * bump.x + b * bump.y + n * max(bump.z, 0.05));
        p.roughness = in.roughness_metallic.x * mr.g;
        p.metallic = in.roughness_metallic.y * mr.b;
    }
    p.roughness = clamp(p.roughness, 0.05, 1.0);
    return p;
}

// What the surroundings send along `dir`, blurred toward the ambient average for rough
// reflections: the room's ceiling and floor bounce (or the sky and ground outdoors).
fn environment(dir: vec3<f32>, roughness: f32) -> vec3<f32> {
    let sharp = mix(g.ground_ambient.rgb * 0.8, g.sky_ambient.rgb * 1.5, smoothstep(-0.3, 0.4, dir.y));
    let soft = (g.sky_ambient.rgb + g.ground_ambient.rgb) * 0.5;
    return mix(sharp, soft, roughness * roughness);
}

// GGX specular lobe times π (the renderer's lights are irradiances: diffuse = albedo × light),
// with Smith–Schlick visibility.
fn specular_lobe(n_h: f32, n_l: f32, n_v: f32, roughness: f32) -> f32 {
    let a = roughness * roughness;
    let a2 = a * a;
    let d = n_h * n_h * (a2 - 1.0) + 1.0;
    let k = a * 0.5;
    let vis = 1.0 / ((n_l * (1.0 - k) + k) * (n_v * (1.0 - k) + k) * 4.0);
    return a2 / (d * d) * vis;
}

// A lit fragment: its colour, the share of that colour that is ambient light (which the
// ambient occlusion darkens), and how much of the environment it reflects at its angle.
struct Lit {
    color: vec3<f32>,
    ambient_share: f32,
    reflectance: f32,
};

// The key light (sun, with its shadow) and the fill (the hemisphere of ceiling and floor
// light, or sky and ground, and its reflection) on a fragment.
fn light(in: Varying, front: bool) -> Lit {
    let s = surface_point(in, front);
    let n = s.normal;
    let v = normalize(g.eye.xyz - in.world);
    let l = g.light_dir.xyz;
    let n_l = max(dot(n, l), 0.0);
    let n_v = max(dot(n, v), 1e-3);
    var shadow = vec3<f32>(1.0);
    let geometric = normalize(in.normal);
    if dot(geometric, l) > 0.0 {
        shadow = sunlight(in.world, geometric);
    }
    let f0 = mix(vec3<f32>(0.04), s.albedo, s.metallic);
    let diffuse_color = s.albedo * (1.0 - s.metallic);
    let h = normalize(l + v);
    let fresnel = f0 + (1.0 - f0) * pow(1.0 - max(dot(h, v), 0.0), 5.0);
    let sun = g.sun.rgb * (n_l * shadow);
    let lobe = specular_lobe(max(dot(n, h), 0.0), n_l, n_v, s.roughness);
    let direct = diffuse_color * sun + fresnel * lobe * sun;
    let ambient_light = mix(g.ground_ambient.rgb, g.sky_ambient.rgb, n.y * 0.5 + 0.5);
    let gloss = (1.0 - s.roughness) * (1.0 - s.roughness);
    let f_env = f0 + (max(vec3<f32>(gloss), f0) - f0) * pow(1.0 - n_v, 5.0);
    let reflected = f_env * environment(reflect(-v, n), s.roughness);
    let ambient = diffuse_color * ambient_light + reflected;
    let weights = vec3<f32>(0.3, 0.6, 0.1);
    var out: Lit;
    out.color = clamp(direct + ambient, vec3<f32>(0.0), vec3<f32>(1.0));
    out.ambient_share = clamp(dot(ambient, weights) / max(dot(direct + ambient, weights), 1e-4), 0.0, 1.0);
    out.reflectance = dot(f_env, weights);
    return out;
}

// Opaque surfaces; see-through ones (opacity below 1) are left to `fs_glass`.
@fragment
fn fs_scene(in: Varying, @builtin(front_facing) front: bool) -> Targets {
    let lit = light(in, front);
    var out: Targets;
    out.color = vec4<f32>(lit.color, lit.ambient_share);
    out.depth = bitcast<u32>(in.depth);
    out.instance = in.instance;
    return out;
}

// See-through surfaces (glass), blended over what the opaque pass drew: their opacity plus
// what they reflect. They leave the depth and instance images to what lies behind them.
@fragment
fn fs_glass(in: Varying, @builtin(front_facing) front: bool) -> Targets {
    let lit = light(in, front);
    var out: Targets;
    out.color = vec4<f32>(lit.color, clamp(in.albedo.a + lit.reflectance, 0.0, 1.0));
    out.depth = 0u;
    out.instance = 0u;
    return out;
}

// The shadow map of the opaque casters (depth only: no fragment stage, the cheap path).
@vertex
fn vs_shadow(v: VertexIn) -> @builtin(position) vec4<f32> {
    if v.albedo.a < 0.999 {
        return CULLED;
    }
    return g.light_from_world * vec4<f32>(v.position, 1.0);
}

struct ShadowVarying {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) albedo: vec4<f32>,
};

// The see-through casters (glass), drawn into the shadow tint.
@vertex
fn vs_shadow_glass(v: VertexIn) -> ShadowVarying {
    var out: ShadowVarying;
    out.albedo = v.albedo;
    out.clip = g.light_from_world * vec4<f32>(v.position, 1.0);
    if v.albedo.a >= 0.999 {
        out.clip = CULLED;
    }
    return out;
}

// Glass lets through the share 1 − opacity of the light, coloured by its hue (its albedo
// scaled so the brightest channel is 1: clear glass casts a grey shadow, green glass a green
// one). The target keeps the minimum over the panes, so a closed pane (two faces) shades
// as much as one face.
@fragment
fn fs_shadow_tint(in: ShadowVarying) -> @location(0) vec4<f32> {
    let c = max(in.albedo.rgb, vec3<f32>(0.0));
    let hue = c / max(max(c.r, max(c.g, c.b)), 1e-4);
    return vec4<f32>((1.0 - in.albedo.a) * hue, in.clip.z);
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
    out.color = vec4<f32>(color, 0.0);
    out.depth = 0u;
    out.instance = 0u;
    return out;
}

@group(1) @binding(0) var lit_color: texture_2d<f32>;
@group(1) @binding(1) var lit_depth: texture_2d<u32>;

// Linear depth at a pixel; 0 where nothing was drawn.
fn depth_at(p: vec2<i32>) -> f32 {
    return bitcast<f32>(textureLoad(lit_depth, p, 0).r);
}

// The camera-frame point (x right, y up, −z forward) a pixel shows at linear depth `d`.
fn camera_point(p: vec2<i32>, d: f32) -> vec3<f32> {
    let k = g.intrinsics;
    return vec3<f32>((f32(p.x) + 0.5 - k.z) / k.x * d, -(f32(p.y) + 0.5 - k.w) / k.y * d, -d);
}

// The neighbour step along `step` that stays on the same surface: of the pixel before and
// after, the one whose depth differs least (background counts as far away).
fn surface_step(p: vec2<i32>, here: vec3<f32>, step: vec2<i32>, size: vec2<i32>) -> vec3<f32> {
    let a = clamp(p + step, vec2<i32>(0), size - 1);
    let b = clamp(p - step, vec2<i32>(0), size - 1);
    let da = depth_at(a);
    let db = depth_at(b);
    let ea = select(1e9, abs(da + here.z), da > 0.0);
    let eb = select(1e9, abs(db + here.z), db > 0.0);
    if ea <= eb {
        return camera_point(a, da) - here;
    }
    return here - camera_point(b, db);
}

// Screen-space ambient occlusion: 12 depth samples on a spiral over a disc of `occlusion.x`
// metres around the point, each occluding by how far it rises above the surface's tangent
// plane, fading out with distance (so depth edges do not halo). The spiral turns by a 2 × 2
// pattern of output pixels (`pattern`).
fn occlusion_at(p: vec2<i32>, d: f32, pattern: vec2<i32>) -> f32 {
    let size = vec2<i32>(textureDimensions(lit_depth));
    let here = camera_point(p, d);
    var n = normalize(cross(surface_step(p, here, vec2<i32>(1, 0), size), surface_step(p, here, vec2<i32>(0, 1), size)));
    if dot(n, here) > 0.0 {
        n = -n;
    }
    let radius_m = g.occlusion.x;
    let radius_px = clamp(radius_m * g.intrinsics.x / d, 2.0, g.occlusion.z);
    let turn = f32((pattern.x & 1) + 2 * (pattern.y & 1)) * (PI * 0.5) + 0.4;
    var occluded = 0.0;
    let count = 12;
    for (var i = 0; i < count; i++) {
        let t = (f32(i) + 0.5) / f32(count);
        let angle = f32(i) * 2.39996 + turn;
        let q = p + vec2<i32>(round(vec2<f32>(cos(angle), sin(angle)) * radius_px * sqrt(t)));
        if any(q < vec2<i32>(0)) || any(q >= size) {
            continue;
        }
        let dq = depth_at(q);
        if dq <= 0.0 {
            continue;
        }
        let to = camera_point(q, dq) - here;
        let dist = length(to);
        let rise = dot(n, to) / max(dist, 1e-4) - 0.1;
        occluded += max(rise, 0.0) * (1.0 - smoothstep(0.5 * radius_m, radius_m, dist));
    }
    return clamp(1.0 - g.occlusion.y * occluded / f32(count), 0.0, 1.0);
}

// The final colour of an output pixel: the `occlusion.w` × `occlusion.w` block of lit
// scene-pass pixels it covers (one for a plain frame, four for a 2× supersampled preview),
// each with its ambient share darkened by the block's ambient occlusion, averaged in linear
// light (the sRGB target encodes it). The occlusion is looked up once per output pixel, at
// the block's nearest surface: supersampled previews pay it at their own size.
@fragment
fn fs_occlusion(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let factor = max(i32(g.occlusion.w), 1);
    let base = vec2<i32>(frag.xy) * factor;
    var nearest = base;
    var nearest_d = 0.0;
    for (var dy = 0; dy < factor; dy++) {
        for (var dx = 0; dx < factor; dx++) {
            let q = base + vec2<i32>(dx, dy);
            let d = depth_at(q);
            if d > 0.0 && (nearest_d <= 0.0 || d < nearest_d) {
                nearest = q;
                nearest_d = d;
            }
        }
    }
    var ao = 1.0;
    if nearest_d > 0.0 && g.occlusion.y > 0.0 {
        ao = occlusion_at(nearest, nearest_d, vec2<i32>(frag.xy));
    }
    var sum = vec3<f32>(0.0);
    for (var dy = 0; dy < factor; dy++) {
        for (var dx = 0; dx < factor; dx++) {
            let lit = textureLoad(lit_color, base + vec2<i32>(dx, dy), 0);
            sum += lit.rgb * (1.0 - lit.a * (1.0 - ao));
        }
    }
    return vec4<f32>(sum / f32(factor * factor), 1.0);
}
