//! Music, media and games furniture: guitar on its stand, drum kit, guitar amplifier, tower
//! speaker, pull-down projector screen, microphone stand, mixing console, recliner, arcade
//! cabinet, foosball table, ping-pong table and dartboard. Fronts face +Z (the side a player,
//! listener or audience faces); wall pieces have their wall side at −Z.

use std::f32::consts::{FRAC_PI_2, PI, TAU};

use nalgebra::{Rotation3, Vector3};
use rand_chacha::ChaCha8Rng;

use super::{mat, mat_either};
use crate::articulation::{self, Leaf, LinkMaterials};
use crate::materials::{fixed_material, Palette};
use crate::random::{coin, int, pick, uniform};
use scenethesis_primitives::{
    cuboid, cylinder, ellipsoid, frustum, prism_x, ring_slab, rod, rotated_box, rotation,
    rounded_box, sphere, strut, transformed, tube, AssetBuilder,
};
use scenethesis_scene_graph::{Asset, MeshPart, Placement};

// --- shared helpers ---

/// A point `p` = (z, y) of a side profile moved `s` metres along the line towards `q` and `h`
/// metres off it along its normal (the normal turned up and toward +Z for a line rising toward
/// −Z). Returns the point and the line's tilt about +X (the angle of [`rotation`] that turns
/// +Y onto that normal).
fn along_slope(p: [f32; 2], q: [f32; 2], s: f32, h: f32) -> ([f32; 2], f32) {
    let (dz, dy) = (q[0] - p[0], q[1] - p[1]);
    let len = (dz * dz + dy * dy).sqrt().max(1e-6);
    let (uz, uy) = (dz / len, dy / len);
    let (nz, ny) = (uy, -uz);
    let tilt = nz.atan2(ny);
    ([p[0] + s * uz + h * nz, p[1] + s * uy + h * ny], tilt)
}

/// A floor tripod under a vertical pole at (`x`, `z`): three splayed legs from a hub at
/// `hub` height out to `reach`, the first pointing along `yaw` (radians from +X toward +Z),
/// and the pole from the hub up to `top`.
#[allow(clippy::too_many_arguments)]
fn tripod(
    b: &mut AssetBuilder,
    name: &str,
    m: usize,
    center: [f32; 2],
    reach: f32,
    hub: f32,
    top: f32,
    yaw: f32,
) {
    let [x, z] = center;
    for k in 0..3 {
        let a = yaw + TAU * k as f32 / 3.0;
        let foot = [x + reach * a.cos(), 0.0, z + reach * a.sin()];
        b.part(strut(
            &format!("{name}_leg_{k}"),
            m,
            foot,
            [x + 0.02 * a.cos(), hub, z + 0.02 * a.sin()],
            [0.018, 0.018],
        ));
    }
    b.part(cylinder(
        &format!("{name}_hub"),
        m,
        [x, z],
        0.02,
        hub - 0.04,
        hub + 0.02,
        10,
    ));
    b.part(rod(
        &format!("{name}_pole"),
        m,
        [x, hub, z],
        [x, top, z],
        0.011,
        0.009,
        10,
    ));
}

/// A drum along the axis from `a` to `c`: a shell of `radius`, a hoop at each end and a pale
/// head just proud of the end at `c` (the batter head).
#[allow(clippy::too_many_arguments)]
fn drum(
    b: &mut AssetBuilder,
    name: &str,
    shell: usize,
    head: usize,
    hoop: usize,
    a: [f32; 3],
    c: [f32; 3],
    radius: f32,
) {
    b.part(rod(
        &format!("{name}_shell"),
        shell,
        a,
        c,
        radius,
        radius,
        24,
    ));
    let axis = Vector3::from(c) - Vector3::from(a);
    let unit = axis / axis.norm().max(1e-6);
    for (k, end) in [a, c].into_iter().enumerate() {
        let e = Vector3::from(end);
        let inward = if k == 0 { unit } else { -unit };
        let (p, q) = (e + inward * 0.018, e - inward * 0.002);
        b.part(rod(
            &format!("{name}_hoop_{k}"),
            hoop,
            p.into(),
            q.into(),
            radius + 0.008,
            radius + 0.008,
            24,
        ));
    }
    let e = Vector3::from(c);
    b.part(rod(
        &format!("{name}_head"),
        head,
        (e - unit * 0.001).into(),
        (e + unit * 0.004).into(),
        radius - 0.004,
        radius - 0.004,
        24,
    ));
}

/// A flat cymbal of `radius` whose underside is at height `y` over (`x`, `z`): a thin disc and
/// a raised bell.
fn cymbal(b: &mut AssetBuilder, name: &str, m: usize, center: [f32; 2], radius: f32, y: f32) {
    b.part(frustum(
        &format!("{name}_disc"),
        m,
        center,
        radius,
        0.25 * radius,
        y,
        y + 0.012,
        28,
    ));
    b.part(frustum(
        &format!("{name}_bell"),
        m,
        center,
        0.22 * radius,
        0.08 * radius,
        y + 0.008,
        y + 0.03,
        16,
    ));
}

// --- guitar ---

/// The proportions of one guitar, in its own upright frame (body bottom at y = 0, soundboard
/// toward +Z, body mid-plane z = 0).
struct GuitarShape {
    /// Radii of the lower and upper bouts.
    lower: f32,
    upper: f32,
    /// Body length and thickness.
    body: f32,
    depth: f32,
    /// Neck length (body to headstock) and width.
    neck: f32,
    neck_w: f32,
    /// Number of strings, and whether it has a sound hole (an acoustic).
    strings: usize,
    acoustic: bool,
}

impl GuitarShape {
    /// Draws an acoustic (lower bout 0.36–0.41 wide, 0.1–0.12 deep), electric (0.32–0.36 wide,
    /// 0.04–0.05 deep) or bass guitar (0.34–0.38 wide, a 0.6–0.65 m neck).
    fn draw(rng: &mut ChaCha8Rng) -> Self {
        match int(rng, 0, 2) {
            0 => {
                let lower = uniform(rng, 0.18, 0.205);
                Self {
                    lower,
                    upper: 0.76 * lower,
                    body: uniform(rng, 0.48, 0.52),
                    depth: uniform(rng, 0.1, 0.12),
                    neck: uniform(rng, 0.42, 0.46),
                    neck_w: 0.05,
                    strings: 6,
                    acoustic: true,
                }
            }
            k => {
                let lower = uniform(rng, 0.16, if k == 1 { 0.18 } else { 0.19 });
                Self {
                    lower,
                    upper: 0.78 * lower,
                    body: uniform(rng, 0.42, 0.46),
                    depth: uniform(rng, 0.04, 0.05),
                    neck: if k == 1 {
                        uniform(rng, 0.38, 0.42)
                    } else {
                        uniform(rng, 0.6, 0.65)
                    },
                    neck_w: if k == 1 { 0.046 } else { 0.055 },
                    strings: if k == 1 { 6 } else { 4 },
                    acoustic: false,
                }
            }
        }
    }

    /// Height of the point where the neck meets the headstock.
    fn nut(&self) -> f32 {
        self.body + self.neck
    }
}

/// The guitar's parts in its own upright frame: the two bouts of the body, a sound hole or
/// pickups, the bridge, the neck with its fingerboard, the headstock with pegs, and strings.
fn guitar_parts(
    g: &GuitarShape,
    finish: usize,
    wood: usize,
    dark: usize,
    metal: usize,
) -> Vec<MeshPart> {
    let hz = 0.5 * g.depth;
    let upper_y = g.body - g.upper;
    let mut parts = vec![
        rod(
            "lower_bout",
            finish,
            [0.0, g.lower, -hz],
            [0.0, g.lower, hz],
            g.lower,
            g.lower,
            28,
        ),
        rod(
            "upper_bout",
            finish,
            [0.0, upper_y, -hz],
            [0.0, upper_y, hz],
            g.upper,
            g.upper,
            24,
        ),
    ];
    if g.acoustic {
        let y = upper_y - 0.2 * g.upper;
        parts.push(rod(
            "sound_hole",
            dark,
            [0.0, y, hz - 0.001],
            [0.0, y, hz + 0.0015],
            0.045,
            0.045,
            20,
        ));
    } else {
        for (k, y) in [0.55 * g.lower + 0.08, 0.55 * g.lower + 0.16]
            .into_iter()
            .enumerate()
        {
            parts.push(cuboid(
                &format!("pickup_{k}"),
                dark,
                [-0.04, y - 0.012, hz - 0.001],
                [0.04, y + 0.012, hz + 0.008],
            ));
        }
    }
    let bridge_y = 0.55 * g.lower;
    parts.push(cuboid(
        "bridge",
        dark,
        [-0.06, bridge_y - 0.015, hz - 0.001],
        [0.06, bridge_y + 0.015, hz + 0.008],
    ));
    let neck_z = [hz.min(0.03) - 0.022, hz.min(0.03) + 0.004];
    let hw = 0.5 * g.neck_w;
    parts.push(cuboid(
        "neck",
        wood,
        [-hw, g.body - 0.06, neck_z[0]],
        [hw, g.nut() + 0.01, neck_z[1]],
    ));
    parts.push(cuboid(
        "fingerboard",
        dark,
        [-hw, g.body - 0.06, neck_z[1] - 0.001],
        [hw, g.nut(), neck_z[1] + 0.005],
    ));
    parts.extend(headstock(g, wood, metal, neck_z));
    parts.extend(strings(g, metal, bridge_y, neck_z[1] + 0.0065));
    parts
}

/// The headstock above the nut and its tuning pegs (half to each side).
fn headstock(g: &GuitarShape, wood: usize, metal: usize, neck_z: [f32; 2]) -> Vec<MeshPart> {
    let (y0, len) = (g.nut(), 0.17);
    let mut parts = vec![cuboid(
        "headstock",
        wood,
        [-0.042, y0, neck_z[0] + 0.004],
        [0.042, y0 + len, neck_z[1]],
    )];
    let per_side = g.strings / 2;
    for k in 0..g.strings {
        let side = if k < per_side { -1.0 } else { 1.0 };
        let y = y0 + 0.035 + (k % per_side) as f32 * (len - 0.05) / per_side as f32;
        let z = 0.5 * (neck_z[0] + neck_z[1]);
        parts.push(rod(
            &format!("peg_{k}"),
            metal,
            [side * 0.04, y, z],
            [side * 0.065, y, z],
            0.006,
            0.006,
            8,
        ));
    }
    parts
}

/// The strings from the bridge to the nut, just above the fingerboard at `z`.
fn strings(g: &GuitarShape, metal: usize, bridge_y: f32, z: f32) -> Vec<MeshPart> {
    let spread = 0.5 * g.neck_w - 0.006;
    (0..g.strings)
        .map(|k| {
            let x = -spread + 2.0 * spread * k as f32 / (g.strings - 1) as f32;
            cuboid(
                &format!("string_{k}"),
                metal,
                [x - 0.0008, bridge_y, z - 0.0008],
                [x + 0.0008, g.nut() + 0.005, z + 0.0008],
            )
        })
        .collect()
}

/// Guitar in a floor stand (body 0.32–0.41 wide, the instrument 0.97–1.28 long, leaning back
/// 12–17°; 1.06–1.39 high on the stand): an acoustic, electric or bass guitar (see [`GuitarShape::draw`]) on a tubular
/// stand of two floor rails, a padded cradle under the body, and a post up to a yoke that
/// holds the neck. The soundboard faces +Z.
pub(super) fn guitar(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let g = GuitarShape::draw(rng);
    let finish = if g.acoustic {
        mat_either(&mut b, 0.7, Palette::Wood, Palette::PaintedWood, rng)
    } else {
        mat_either(
            &mut b,
            0.5,
            Palette::PaintedWood,
            Palette::BrightPlastic,
            rng,
        )
    };
    let wood = mat(&mut b, Palette::Wood, rng);
    let dark = b.material(fixed_material("rosewood", [0x2A, 0x1C, 0x16], 0.6, 0.0));
    let metal = mat(&mut b, Palette::Metal, rng);
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let pad = b.material(fixed_material("foam_pad", [0x1C, 0x1C, 0x1E], 0.9, 0.0));
    let lean = uniform(rng, 0.21, 0.3);
    let rot = rotation([1.0, 0.0, 0.0], -lean);
    let cradle = uniform(rng, 0.1, 0.14);
    let offset = [0.0, cradle + 0.5 * g.depth * lean.sin(), 0.0];
    for part in guitar_parts(&g, finish, wood, dark, metal) {
        b.part(transformed(part, &rot, offset));
    }
    guitar_stand(&mut b, &g, [frame, pad], (&rot, lean), offset);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// The stand under a guitar placed by `rot` (a lean of `lean` radians) and `offset`: rails, cradle with a front lip, a
/// post and a padded yoke (built in the guitar's frame so it meets the neck).
fn guitar_stand(
    b: &mut AssetBuilder,
    g: &GuitarShape,
    [frame, pad]: [usize; 2],
    (rot, lean): (&Rotation3<f32>, f32),
    offset: [f32; 3],
) {
    let hz = 0.5 * g.depth;
    let yoke_y = g.body + 0.75 * g.neck;
    let local = |p: [f32; 3]| rot * Vector3::from(p) + Vector3::from(offset);
    let neck_back = hz.min(0.03) - 0.022;
    let post_top = local([0.0, yoke_y, neck_back - 0.03]);
    let cradle_y = offset[1] - 0.5 * g.depth * lean.sin();
    let (front, back) = (hz + 0.06, post_top.z - 0.14);
    for (k, x) in [-0.16f32, 0.16].into_iter().enumerate() {
        b.cuboid(
            &format!("rail_{k}"),
            frame,
            [x - 0.0125, 0.0, back],
            [x + 0.0125, 0.022, front],
        );
        b.cuboid(
            &format!("cradle_post_{k}"),
            frame,
            [x - 0.01, 0.02, -0.01],
            [x + 0.01, cradle_y, 0.01],
        );
    }
    b.cuboid(
        "rail_back",
        frame,
        [-0.16, 0.0, back],
        [0.16, 0.022, back + 0.025],
    );
    b.cuboid(
        "cradle",
        pad,
        [-0.17, cradle_y - 0.02, -hz - 0.02],
        [0.17, cradle_y + 0.002, hz + 0.03],
    );
    b.cuboid(
        "cradle_lip",
        pad,
        [-0.17, cradle_y - 0.02, hz + 0.012],
        [0.17, cradle_y + 0.045, hz + 0.03],
    );
    b.part(rod(
        "post",
        frame,
        [0.0, 0.011, back + 0.0125],
        post_top.into(),
        0.011,
        0.011,
        10,
    ));
    let yoke = |name: &str, x: [f32; 2], z: [f32; 2]| {
        let part = cuboid(
            name,
            pad,
            [x[0], yoke_y - 0.015, z[0]],
            [x[1], yoke_y + 0.015, z[1]],
        );
        transformed(part, rot, offset)
    };
    let z_back = neck_back - 0.035;
    b.part(yoke("yoke", [-0.045, 0.045], [z_back, neck_back - 0.001]));
    b.part(yoke(
        "yoke_left",
        [-0.045, -0.03],
        [z_back, neck_back + 0.035],
    ));
    b.part(yoke(
        "yoke_right",
        [0.03, 0.045],
        [z_back, neck_back + 0.035],
    ));
}

// --- drum kit ---

/// Drum kit (footprint 1.43–1.55 wide × 1.29–1.32 deep, 1.13–1.38 high with its cymbals): a bass
/// drum (0.5–0.56 across) facing the audience (+Z) with one or two rack toms on it, a snare
/// and a hi-hat on tripod stands, a floor tom on three legs, a crash cymbal (and sometimes a
/// ride) on stands, pedals, and a padded throne behind it all.
pub(super) fn drum_kit(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let shell = mat_either(&mut b, 0.5, Palette::BrightPlastic, Palette::Wood, rng);
    let head = b.material(fixed_material("drum_head", [0xEE, 0xEA, 0xDE], 0.7, 0.0));
    let chrome = b.material(fixed_material("chrome", [0xDD, 0xDE, 0xE0], 0.15, 1.0));
    let bronze = b.material(fixed_material("cymbal", [0xC8, 0x9A, 0x48], 0.25, 1.0));
    let seat = mat(&mut b, Palette::Leather, rng);
    let kick_r = uniform(rng, 0.25, 0.28);
    let kick_d = uniform(rng, 0.36, 0.45);
    let kick_z = 0.12;
    drum(
        &mut b,
        "bass_drum",
        shell,
        head,
        chrome,
        [0.0, kick_r + 0.01, kick_z - 0.5 * kick_d],
        [0.0, kick_r + 0.01, kick_z + 0.5 * kick_d],
        kick_r,
    );
    for (k, x) in [-0.2f32, 0.2].into_iter().enumerate() {
        b.part(strut(
            &format!("spur_{k}"),
            chrome,
            [x * 1.35, 0.0, kick_z + 0.25 * kick_d],
            [x, 0.12, kick_z + 0.25 * kick_d],
            [0.014, 0.014],
        ));
    }
    let kick_top = 2.0 * kick_r + 0.01;
    rack_toms(&mut b, [shell, head, chrome], kick_top, kick_z, rng);
    floor_tom(&mut b, [shell, head, chrome], rng);
    snare_and_hihat(&mut b, [shell, head, chrome, bronze], kick_z - 0.5 * kick_d);
    cymbal_stands(&mut b, chrome, bronze, rng);
    tripod(
        &mut b,
        "throne",
        chrome,
        [0.0, -0.56],
        0.22,
        0.22,
        0.46,
        -FRAC_PI_2,
    );
    let seat_h = uniform(rng, 0.5, 0.58);
    b.part(cylinder(
        "throne_seat",
        seat,
        [0.0, -0.56],
        0.17,
        seat_h - 0.08,
        seat_h,
        24,
    ));
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// One or two rack toms on a mount rising from the bass drum's shell, tilted toward the
/// drummer (−Z).
fn rack_toms(
    b: &mut AssetBuilder,
    m: [usize; 3],
    kick_top: f32,
    kick_z: f32,
    rng: &mut ChaCha8Rng,
) {
    let [shell, head, chrome] = m;
    let n = int(rng, 1, 2);
    let r = uniform(rng, 0.15, 0.165);
    let tilt = uniform(rng, 0.25, 0.4);
    let axis = Vector3::new(0.0, tilt.cos(), -tilt.sin());
    for k in 0..n {
        let x = if n == 1 { 0.12 } else { [-0.17, 0.17][k] };
        let c = Vector3::new(x, kick_top + 0.2, kick_z - 0.05);
        drum(
            b,
            &format!("rack_tom_{k}"),
            shell,
            head,
            chrome,
            (c - axis * 0.1).into(),
            (c + axis * 0.1).into(),
            r,
        );
        b.part(rod(
            &format!("tom_mount_{k}"),
            chrome,
            [0.5 * x, kick_top - 0.02, kick_z],
            (c - axis * 0.1).into(),
            0.011,
            0.011,
            8,
        ));
    }
}

/// A floor tom on three legs at the drummer's right (−X).
fn floor_tom(b: &mut AssetBuilder, m: [usize; 3], rng: &mut ChaCha8Rng) {
    let [shell, head, chrome] = m;
    let r = uniform(rng, 0.19, 0.21);
    let (x, z) = (-0.44, -0.14);
    let top = uniform(rng, 0.56, 0.62);
    let depth = uniform(rng, 0.36, 0.41);
    drum(
        b,
        "floor_tom",
        shell,
        head,
        chrome,
        [x, top - depth, z],
        [x, top, z],
        r,
    );
    for k in 0..3 {
        let a = FRAC_PI_2 + TAU * k as f32 / 3.0;
        let (dx, dz) = (a.cos(), a.sin());
        b.part(strut(
            &format!("floor_tom_leg_{k}"),
            chrome,
            [x + (r + 0.05) * dx, 0.0, z + (r + 0.05) * dz],
            [x + (r + 0.015) * dx, top - 0.06, z + (r + 0.015) * dz],
            [0.014, 0.014],
        ));
    }
}

/// The snare on its stand and the hi-hat with its pedal at the drummer's left (+X), and the
/// bass drum pedal behind the bass drum (whose back is at `kick_back`).
fn snare_and_hihat(b: &mut AssetBuilder, m: [usize; 4], kick_back: f32) {
    let [shell, head, chrome, bronze] = m;
    let (sx, sz, top) = (0.3, -0.24, 0.64);
    tripod(
        b,
        "snare_stand",
        chrome,
        [sx, sz],
        0.2,
        0.2,
        top - 0.14,
        FRAC_PI_2,
    );
    drum(
        b,
        "snare",
        shell,
        head,
        chrome,
        [sx, top - 0.14, sz],
        [sx, top, sz],
        0.178,
    );
    let (hx, hz) = (0.6, -0.08);
    tripod(b, "hihat_stand", chrome, [hx, hz], 0.2, 0.2, 0.92, PI);
    cymbal(b, "hihat_bottom", bronze, [hx, hz], 0.178, 0.86);
    cymbal(b, "hihat_top", bronze, [hx, hz], 0.178, 0.885);
    b.cuboid(
        "hihat_pedal",
        chrome,
        [hx - 0.05, 0.0, hz - 0.3],
        [hx + 0.05, 0.03, hz - 0.03],
    );
    b.cuboid(
        "kick_pedal",
        chrome,
        [-0.05, 0.0, kick_back - 0.28],
        [0.05, 0.03, kick_back + 0.01],
    );
}

/// A crash cymbal on a stand at the drummer's front left, and sometimes a ride at the front
/// right.
fn cymbal_stands(b: &mut AssetBuilder, chrome: usize, bronze: usize, rng: &mut ChaCha8Rng) {
    let crash_h = uniform(rng, 1.1, 1.35);
    let (cx, cz) = (0.45, 0.3);
    tripod(b, "crash_stand", chrome, [cx, cz], 0.22, 0.22, crash_h, 0.3);
    cymbal(
        b,
        "crash",
        bronze,
        [cx, cz],
        uniform(rng, 0.2, 0.23),
        crash_h,
    );
    if coin(rng, 0.6) {
        let ride_h = uniform(rng, 1.0, 1.15);
        let (rx, rz) = (-0.5, 0.22);
        tripod(
            b,
            "ride_stand",
            chrome,
            [rx, rz],
            0.22,
            0.22,
            ride_h,
            PI - 0.3,
        );
        cymbal(
            b,
            "ride",
            bronze,
            [rx, rz],
            uniform(rng, 0.24, 0.27),
            ride_h,
        );
    }
}

// --- amplifier and speaker ---

/// Guitar amplifier (a combo: width 0.42–0.66, height 0.4–0.58, depth 0.22–0.3 as made by
/// common 1×12 and 2×12 combos): a tolex-covered cabinet on four rubber feet with metal
/// corners, a cloth grille over the front, a control plate with knobs along the back of the
/// top, a carry handle in front of it, and the rest of the top usable.
pub(super) fn amplifier(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let tolex = b.material(pick_tolex(rng));
    let grille = mat_either(&mut b, 0.5, Palette::Fabric, Palette::Plastic, rng);
    let metal = mat(&mut b, Palette::Metal, rng);
    let knob = b.material(fixed_material("knob", [0x18, 0x18, 0x1A], 0.5, 0.0));
    let (w, h, d) = (
        uniform(rng, 0.42, 0.66),
        uniform(rng, 0.4, 0.58),
        uniform(rng, 0.22, 0.3),
    );
    let (hw, hd, foot) = (0.5 * w, 0.5 * d, 0.015);
    for (i, (sx, sz)) in super::carcass::CORNERS.iter().enumerate() {
        b.cuboid(
            &format!("foot_{i}"),
            knob,
            [sx * (hw - 0.03) - 0.015, 0.0, sz * (hd - 0.03) - 0.015],
            [
                sx * (hw - 0.03) + 0.015,
                foot + 0.001,
                sz * (hd - 0.03) + 0.015,
            ],
        );
    }
    b.cuboid("cabinet", tolex, [-hw, foot, -hd], [hw, h, hd]);
    b.cuboid(
        "grille",
        grille,
        [-hw + 0.03, foot + 0.03, hd - 0.002],
        [hw - 0.03, h - 0.03, hd + 0.004],
    );
    b.cuboid(
        "logo",
        metal,
        [-0.05, h - 0.075, hd + 0.003],
        [0.05, h - 0.055, hd + 0.007],
    );
    for (i, (sx, sy)) in [(-1.0f32, 0.0f32), (1.0, 0.0), (-1.0, 1.0), (1.0, 1.0)]
        .into_iter()
        .enumerate()
    {
        let (x, y) = (sx * (hw - 0.015), foot + 0.017 + sy * (h - foot - 0.034));
        b.cuboid(
            &format!("corner_{i}"),
            metal,
            [x - 0.017, y - 0.017, hd - 0.03],
            [x + 0.017, y + 0.017, hd + 0.005],
        );
    }
    amp_controls(&mut b, [metal, knob], hw, hd, h, rng);
    b.top_surface("top", [-hw, -hd + 0.12], [hw, hd], h, 0.03);
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// A tolex colour: black mostly, sometimes cream, brown or red.
fn pick_tolex(rng: &mut ChaCha8Rng) -> scenethesis_scene_graph::Material {
    let (name, rgb) = *pick(
        rng,
        &[
            ("black_tolex", [0x1E, 0x1E, 0x20]),
            ("black_tolex", [0x24, 0x22, 0x22]),
            ("cream_tolex", [0xE2, 0xD6, 0xB8]),
            ("brown_tolex", [0x5A, 0x3C, 0x2A]),
            ("red_tolex", [0x8A, 0x22, 0x22]),
        ],
    );
    fixed_material(name, rgb, 0.8, 0.0)
}

/// The control plate with a row of knobs along the back of the top, and the carry handle.
fn amp_controls(
    b: &mut AssetBuilder,
    [metal, knob]: [usize; 2],
    hw: f32,
    hd: f32,
    h: f32,
    rng: &mut ChaCha8Rng,
) {
    let z = -hd + 0.045;
    b.cuboid(
        "control_plate",
        metal,
        [-hw + 0.04, h - 0.001, -hd + 0.015],
        [hw - 0.04, h + 0.004, -hd + 0.075],
    );
    let knobs = int(rng, 4, 8);
    let span = 2.0 * hw - 0.14;
    for k in 0..knobs {
        let x = -0.5 * span + span * k as f32 / (knobs - 1) as f32;
        b.part(cylinder(
            &format!("knob_{k}"),
            knob,
            [x, z],
            0.011,
            h + 0.003,
            h + 0.022,
            12,
        ));
    }
    b.cuboid(
        "handle",
        knob,
        [-0.09, h - 0.001, -hd + 0.085],
        [0.09, h + 0.025, -hd + 0.11],
    );
}

/// Tower speaker (floor-standing loudspeaker: cabinet width 0.17–0.28, height 0.86–1.15, depth
/// 0.24–0.36; the plinth 2 cm wider all round): a veneered cabinet on a plinth with four feet, a dark front baffle with a dome
/// tweeter near the top and two or three woofer cones below it, a bass port, and a usable top.
pub(super) fn speaker(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.55, Palette::Wood, Palette::PaintedWood, rng);
    let baffle = b.material(fixed_material("baffle", [0x1A, 0x1A, 0x1C], 0.6, 0.0));
    let cone = mat_either(&mut b, 0.5, Palette::Plastic, Palette::Metal, rng);
    let rubber = b.material(fixed_material("surround", [0x10, 0x10, 0x12], 0.9, 0.0));
    let (w, h, d) = (
        uniform(rng, 0.17, 0.28),
        uniform(rng, 0.86, 1.15),
        uniform(rng, 0.24, 0.36),
    );
    let (hw, hd, plinth) = (0.5 * w, 0.5 * d, 0.04);
    for (i, (sx, sz)) in super::carcass::CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hw + 0.005), sz * (hd + 0.005));
        b.part(cylinder(
            &format!("foot_{i}"),
            rubber,
            [x, z],
            0.012,
            0.0,
            0.016,
            10,
        ));
    }
    b.cuboid(
        "plinth",
        baffle,
        [-hw - 0.02, 0.015, -hd - 0.02],
        [hw + 0.02, plinth, hd + 0.02],
    );
    b.cuboid("cabinet", body, [-hw, plinth - 0.001, -hd], [hw, h, hd]);
    let zf = hd + 0.004;
    b.cuboid(
        "baffle",
        baffle,
        [-hw + 0.008, plinth + 0.01, hd - 0.001],
        [hw - 0.008, h - 0.01, zf],
    );
    let r = (hw - 0.02).min(0.085);
    let tweeter_y = h - 0.09;
    driver(
        &mut b,
        "tweeter",
        [rubber, cone],
        [0.0, tweeter_y],
        0.035,
        zf,
    );
    // As many woofers as fit between the tweeter and the port (two or three drawn).
    let room = tweeter_y - 0.09 - (plinth + 0.15);
    let woofers = int(rng, 2, 3).min(((room + 0.03) / (2.0 * r + 0.03)) as usize);
    for k in 0..woofers {
        let y = tweeter_y - 0.09 - r - k as f32 * (2.0 * r + 0.03);
        driver(
            &mut b,
            &format!("woofer_{k}"),
            [rubber, cone],
            [0.0, y],
            r,
            zf,
        );
    }
    b.part(rod(
        "port",
        rubber,
        [0.0, plinth + 0.09, zf - 0.002],
        [0.0, plinth + 0.09, zf + 0.004],
        0.025,
        0.025,
        16,
    ));
    b.top_surface("top", [-hw, -hd], [hw, hd], h, 0.02);
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// A driver on the baffle whose face is at `zf`: a rubber surround of `radius`, a cone inside
/// it and a dust-cap dome in the middle, centred at (x, y) = `at`.
fn driver(
    b: &mut AssetBuilder,
    name: &str,
    [rubber, cone]: [usize; 2],
    at: [f32; 2],
    radius: f32,
    zf: f32,
) {
    let [x, y] = at;
    b.part(rod(
        &format!("{name}_surround"),
        rubber,
        [x, y, zf - 0.001],
        [x, y, zf + 0.008],
        radius,
        radius,
        24,
    ));
    b.part(rod(
        &format!("{name}_cone"),
        cone,
        [x, y, zf + 0.006],
        [x, y, zf + 0.01],
        0.82 * radius,
        0.5 * radius,
        24,
    ));
    b.part(ellipsoid(
        &format!("{name}_cap"),
        rubber,
        [x, y, zf + 0.01],
        [0.3 * radius, 0.3 * radius, 0.12 * radius],
        6,
        12,
    ));
}

// --- projector screen ---

/// Pull-down projector screen (housing 1.54–2.74 wide, 1.1–2.1 high pulled down, 0.07–0.1
/// deep): a case with end caps on two wall brackets, a matte white sheet with black borders
/// hanging from it, and a weighted bottom bar with a pull tab.
pub(super) fn projector_screen(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let case = mat_either(&mut b, 0.6, Palette::CoatedMetal, Palette::Plastic, rng);
    let sheet = b.material(fixed_material("screen_white", [0xF2, 0xF2, 0xF0], 0.9, 0.0));
    let border = b.material(fixed_material(
        "screen_border",
        [0x16, 0x16, 0x18],
        0.9,
        0.0,
    ));
    let w = uniform(rng, 1.5, 2.7);
    let drop = uniform(rng, 1.0, 1.95).min(0.75 * w + 0.1);
    let case_d = uniform(rng, 0.07, 0.1);
    let (hw, sw, zc) = (0.5 * w, 0.5 * w - 0.07, 0.5 * case_d);
    let top = drop + case_d;
    b.cuboid(
        "case",
        case,
        [-hw + 0.02, drop, 0.0],
        [hw - 0.02, top, case_d],
    );
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        b.cuboid(
            &format!("end_cap_{k}"),
            case,
            [sx * hw - 0.02, drop - 0.005, 0.0],
            [sx * hw + 0.02, top + 0.005, case_d + 0.004],
        );
        let x = sx * (hw - 0.25);
        b.cuboid(
            &format!("bracket_{k}"),
            border,
            [x - 0.03, drop + 0.01, 0.0],
            [x + 0.03, top + 0.02, 0.012],
        );
    }
    b.cuboid(
        "sheet",
        sheet,
        [-sw, 0.03, zc - 0.0015],
        [sw, drop + 0.001, zc + 0.0015],
    );
    let black_top = uniform(rng, 0.05, 0.3).min(0.2 * drop);
    b.cuboid(
        "border_top",
        border,
        [-sw, drop - black_top, zc + 0.001],
        [sw, drop, zc + 0.002],
    );
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        b.cuboid(
            &format!("border_{k}"),
            border,
            [sx * sw - 0.03, 0.03, zc + 0.001],
            [sx * sw + 0.0, drop, zc + 0.002],
        );
    }
    b.cuboid(
        "bottom_bar",
        case,
        [-sw - 0.005, 0.03, zc - 0.01],
        [sw + 0.005, 0.055, zc + 0.01],
    );
    b.cuboid(
        "pull_tab",
        border,
        [-0.02, 0.0, zc - 0.004],
        [0.02, 0.031, zc + 0.004],
    );
    b.finish(Placement::Wall, [0.85, 1.1])
}

// --- microphone stand ---

/// Microphone stand (1.03–1.54 high overall, tripod 0.45–0.56 across): a tripod
/// base, a two-stage pole with a clutch, and either a boom (0.6–0.85 long, raised 15–35°,
/// counterweight at its back end) reaching forward (+Z) or a straight top, ending in a clip
/// holding a microphone with a ball grille.
pub(super) fn microphone_stand(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let mic_body = b.material(fixed_material("mic_body", [0x22, 0x22, 0x24], 0.4, 0.6));
    let grille = mat(&mut b, Palette::Metal, rng);
    let pole_h = uniform(rng, 0.9, 1.25);
    let reach = uniform(rng, 0.25, 0.31);
    tripod(
        &mut b,
        "base",
        frame,
        [0.0, 0.0],
        reach,
        0.2,
        pole_h,
        FRAC_PI_2,
    );
    b.part(cylinder(
        "clutch",
        frame,
        [0.0, 0.0],
        0.016,
        0.62 * pole_h,
        0.62 * pole_h + 0.05,
        10,
    ));
    let top = Vector3::new(0.0, pole_h, 0.0);
    let (mic_at, dir) = if coin(rng, 0.7) {
        let rise = uniform(rng, 0.26, 0.6);
        let dir = Vector3::new(0.0, rise.sin(), rise.cos());
        let (front, back) = (uniform(rng, 0.4, 0.55), uniform(rng, 0.2, 0.3));
        let (f, k) = (top + dir * front, top - dir * back);
        b.part(sphere("boom_clutch", frame, top.into(), 0.025, 6, 10));
        b.part(rod("boom", frame, k.into(), f.into(), 0.009, 0.008, 10));
        b.part(rod(
            "counterweight",
            frame,
            k.into(),
            (k + dir * 0.08).into(),
            0.022,
            0.022,
            12,
        ));
        let tip = Vector3::new(0.0, uniform(rng, -0.3, 0.1), 1.0).normalize();
        (f, tip)
    } else {
        (top, Vector3::new(0.0, 0.6, 0.8))
    };
    b.part(sphere("clip", frame, mic_at.into(), 0.017, 6, 10));
    let (a, c) = (mic_at + dir * 0.01, mic_at + dir * 0.15);
    b.part(tube(
        "microphone",
        mic_body,
        a.into(),
        c.into(),
        0.016,
        0.022,
        14,
    ));
    b.part(sphere(
        "grille",
        grille,
        (c + dir * 0.022).into(),
        0.029,
        8,
        14,
    ));
    b.finish(Placement::Floor, [0.9, 1.1])
}

// --- mixing console ---

/// Mixing console on its desk (width 1.0–1.8, height 1.02–1.18 to the meter bridge, depth
/// 0.75–0.91 with the armrest): two side panels and a back panel round a knee space, the console on top with a
/// control surface sloping up toward the back (a fader, a mute button and knobs per channel,
/// 8–24 channels), a padded armrest along the front, and a meter bridge at the back whose flat
/// top holds monitors.
pub(super) fn mixing_console(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let desk = mat_either(&mut b, 0.5, Palette::Wood, Palette::PaintedWood, rng);
    let panel = mat_either(&mut b, 0.6, Palette::CoatedMetal, Palette::Plastic, rng);
    let dark = b.material(fixed_material("console_dark", [0x16, 0x16, 0x18], 0.5, 0.0));
    let caps = b.material(fixed_material("fader_cap", [0xD8, 0xD8, 0xD4], 0.4, 0.0));
    let pad = mat(&mut b, Palette::Leather, rng);
    let (w, d) = (uniform(rng, 1.0, 1.8), uniform(rng, 0.7, 0.86));
    let y0 = uniform(rng, 0.72, 0.78);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    for (k, x) in [[-hw, -hw + 0.03], [hw - 0.03, hw]].into_iter().enumerate() {
        b.cuboid(
            &format!("side_{k}"),
            desk,
            [x[0], 0.0, -hd],
            [x[1], y0, hd - 0.04],
        );
    }
    b.cuboid(
        "back_panel",
        desk,
        [-hw + 0.02, 0.08, -hd],
        [hw - 0.02, y0, -hd + 0.02],
    );
    let bridge_d = uniform(rng, 0.14, 0.2);
    let rise = uniform(rng, 0.15, 0.22);
    let bridge_top = y0 + rise + uniform(rng, 0.14, 0.2);
    let zb = -hd + bridge_d;
    let (front, back) = ([hd, y0 + 0.06], [zb, y0 + rise]);
    b.part(prism_x(
        "console",
        panel,
        &[[hd, y0 - 0.001], front, back, [zb, y0 - 0.001]],
        -hw,
        hw,
    ));
    b.cuboid(
        "meter_bridge",
        panel,
        [-hw, y0 - 0.001, -hd],
        [hw, bridge_top, zb + 0.001],
    );
    b.cuboid(
        "meters",
        dark,
        [-hw + 0.04, back[1] + 0.03, zb],
        [hw - 0.04, bridge_top - 0.03, zb + 0.004],
    );
    b.part(rod(
        "armrest",
        pad,
        [-hw, y0 + 0.03, hd + 0.015],
        [hw, y0 + 0.03, hd + 0.015],
        0.035,
        0.035,
        12,
    ));
    channel_strips(&mut b, [dark, caps], hw, front, back);
    b.top_surface("bridge", [-hw, -hd], [hw, zb], bridge_top, 0.03);
    b.finish(Placement::Floor, [0.9, 1.1])
}

/// The channel strips on the control surface sloping from `front` to `back` (side profile
/// points (z, y)): per channel a fader slot and cap near the front, a mute button and a
/// column of knobs behind.
fn channel_strips(
    b: &mut AssetBuilder,
    [dark, caps]: [usize; 2],
    hw: f32,
    front: [f32; 2],
    back: [f32; 2],
) {
    let pitch = 0.05;
    let channels = (((2.0 * hw - 0.16) / pitch) as usize).clamp(8, 24);
    let span = channels as f32 * pitch;
    let len = ((back[0] - front[0]).powi(2) + (back[1] - front[1]).powi(2)).sqrt();
    let ([sz, sy], tilt) = along_slope(front, back, 0.07 + 0.08, 0.001);
    let rot = rotation([1.0, 0.0, 0.0], tilt);
    b.part(rotated_box(
        "fader_panel",
        dark,
        [0.0, sy, sz],
        [0.5 * span, 0.002, 0.08],
        &rot,
    ));
    for c in 0..channels {
        let x = -0.5 * span + (c as f32 + 0.5) * pitch;
        let s = 0.07 + 0.02 + 0.12 * ((c * 7 % 5) as f32 / 5.0);
        let ([fz, fy], _) = along_slope(front, back, s, 0.008);
        b.part(rotated_box(
            &format!("fader_{c}"),
            caps,
            [x, fy, fz],
            [0.012, 0.007, 0.008],
            &rot,
        ));
        let knobs = ((len - 0.3) / 0.05).clamp(1.0, 4.0) as usize;
        for k in 0..knobs {
            let ([kz, ky], _) = along_slope(front, back, 0.28 + k as f32 * 0.05, 0.0);
            let n = Vector3::new(0.0, tilt.cos(), tilt.sin());
            let base = Vector3::new(x, ky, kz);
            b.part(tube(
                &format!("knob_{c}_{k}"),
                dark,
                (base - n * 0.002).into(),
                (base + n * 0.016).into(),
                0.009,
                0.008,
                8,
            ));
        }
    }
}

// --- recliner ---

/// Recliner (home-theatre seat: width 0.8–1.0, height 0.98–1.1, depth 0.86–1.0 closed): an
/// upholstered base on low feet, two padded arms, a seat cushion, a thick back leaning back,
/// a release lever on the right arm, and a footrest panel hanging folded under the seat's
/// front that swings up to level (a joint, closed = 0).
pub(super) fn recliner(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let cover = mat_either(&mut b, 0.55, Palette::Leather, Palette::Fabric, rng);
    let dark = b.material(fixed_material("feet", [0x1A, 0x1A, 0x1A], 0.7, 0.0));
    let (w, seat_h) = (uniform(rng, 0.8, 1.0), uniform(rng, 0.46, 0.52));
    let (d, back_h) = (uniform(rng, 0.78, 0.92), uniform(rng, 0.98, 1.1));
    let arm_w = uniform(rng, 0.12, 0.18);
    let arm_h = seat_h + uniform(rng, 0.16, 0.22);
    let (hw, hd) = (0.5 * w, 0.5 * d);
    let (zf, base_y, foot) = (hd, seat_h - 0.14, 0.05);
    let inner = hw - arm_w;
    for (i, (sx, sz)) in super::carcass::CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hw - 0.06), sz * (hd - 0.08));
        b.cuboid(
            &format!("foot_{i}"),
            dark,
            [x - 0.025, 0.0, z - 0.025],
            [x + 0.025, foot + 0.002, z + 0.025],
        );
    }
    b.cuboid(
        "base",
        cover,
        [-inner - 0.01, foot, -hd + 0.05],
        [inner + 0.01, base_y, zf],
    );
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let cx = sx * (hw - 0.5 * arm_w);
        b.part(rounded_box(
            &format!("arm_{k}"),
            cover,
            [cx, 0.5 * (foot + arm_h), 0.0],
            [0.5 * arm_w, 0.5 * (arm_h - foot), hd],
            0.35,
        ));
    }
    let back_front = -hd + uniform(rng, 0.26, 0.32);
    b.part(rounded_box(
        "seat_cushion",
        cover,
        [
            0.0,
            0.5 * (base_y + seat_h) - 0.01,
            0.5 * (back_front - 0.04 + zf),
        ],
        [
            inner,
            0.5 * (seat_h - base_y) + 0.01,
            0.5 * (zf - back_front + 0.04),
        ],
        0.3,
    ));
    b.part(prism_x(
        "back",
        cover,
        &[
            [-hd, foot],
            [back_front, base_y],
            [-hd + 0.14, back_h - 0.05],
            [-hd + 0.03, back_h],
        ],
        -inner - 0.01,
        inner + 0.01,
    ));
    b.cuboid(
        "lever",
        dark,
        [hw - 0.001, seat_h - 0.05, zf - 0.25],
        [hw + 0.012, seat_h - 0.02, zf - 0.12],
    );
    b.top_surface(
        "seat",
        [-inner, back_front + 0.02],
        [inner, zf],
        seat_h,
        0.05,
    );
    footrest(&mut b, cover, inner - 0.02, [0.12, base_y - 0.01], zf);
    b.finish(Placement::Floor, [0.92, 1.08])
}

/// The footrest: a padded panel across `half` either side of x = 0 from `y[0]` up to `y[1]`
/// just in front of the base (face `zf`), hinged along its top front edge so that opening
/// swings its foot forward and up to level.
fn footrest(b: &mut AssetBuilder, cover: usize, half: f32, y: [f32; 2], zf: f32) {
    let t = 0.07;
    b.joint(articulation::back_hinge("footrest", y[1], zf + t, 1.45));
    b.link(Some("footrest"));
    b.part(rounded_box(
        "footrest",
        cover,
        [0.0, 0.5 * (y[0] + y[1]), zf + 0.5 * t],
        [half, 0.5 * (y[1] - y[0]), 0.5 * t],
        0.3,
    ));
    b.link(None);
}

// --- arcade cabinet ---

/// Arcade cabinet (upright: width 0.6–0.78, height 1.7–1.9, depth 0.78–0.95): a cabinet between
/// two shaped side panels, a coin door on the lower front, a control panel overhanging at
/// 0.86–0.94 with one or two joysticks and their buttons, a screen leaning back behind it,
/// and a lit marquee at the top.
pub(super) fn arcade_cabinet(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(
        &mut b,
        0.6,
        Palette::PaintedWood,
        Palette::BrightPlastic,
        rng,
    );
    let side = mat_either(
        &mut b,
        0.5,
        Palette::BrightPlastic,
        Palette::PaintedWood,
        rng,
    );
    let dark = b.material(fixed_material("bezel", [0x12, 0x12, 0x14], 0.4, 0.0));
    let screen = b.material(fixed_material(
        "arcade_screen",
        [0x1C, 0x3A, 0x5C],
        0.05,
        0.0,
    ));
    let lit = b.material(fixed_material("marquee", [0xF4, 0xD0, 0x60], 0.3, 0.0));
    let metal = mat(&mut b, Palette::Metal, rng);
    let (w, h, d) = (
        uniform(rng, 0.6, 0.78),
        uniform(rng, 1.7, 1.9),
        uniform(rng, 0.78, 0.95),
    );
    let py = uniform(rng, 0.86, 0.94);
    let (hw, hd, t) = (0.5 * w, 0.5 * d, 0.02);
    let s = ArcadeProfile {
        hd,
        py,
        zp: hd - uniform(rng, 0.28, 0.34),
        my: h - uniform(rng, 0.2, 0.26),
        h,
    };
    arcade_sides(&mut b, side, &s, hw, t);
    let inner = hw - t + 0.001;
    b.cuboid(
        "lower_cabinet",
        body,
        [-inner, 0.0, -hd],
        [inner, s.py - 0.13, hd - 0.12],
    );
    b.part(prism_x("control_panel", body, &s.panel(), -inner, inner));
    b.part(prism_x(
        "screen_housing",
        body,
        &s.screen_block(),
        -inner,
        inner,
    ));
    b.cuboid(
        "marquee_box",
        body,
        [-inner, s.my - 0.001, -hd],
        [inner, h, s.zp + 0.03],
    );
    b.cuboid(
        "marquee",
        lit,
        [-inner + 0.02, s.my + 0.02, s.zp + 0.029],
        [inner - 0.02, h - 0.03, s.zp + 0.034],
    );
    arcade_screen(&mut b, [dark, screen], &s, inner);
    b.cuboid(
        "coin_door",
        metal,
        [-0.11, 0.38, hd - 0.121],
        [0.11, 0.62, hd - 0.114],
    );
    for (k, x) in [-0.05f32, 0.05].into_iter().enumerate() {
        b.cuboid(
            &format!("coin_slot_{k}"),
            lit,
            [x - 0.015, 0.52, hd - 0.115],
            [x + 0.015, 0.57, hd - 0.11],
        );
    }
    arcade_controls(&mut b, [dark, metal], &s, inner, rng);
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// The side profile of an arcade cabinet, (z, y) points: the control panel's front top at
/// `py`, its back (and the screen's foot) at `zp`, the marquee from `my` up to `h`.
struct ArcadeProfile {
    hd: f32,
    py: f32,
    zp: f32,
    my: f32,
    h: f32,
}

impl ArcadeProfile {
    /// The control panel's side profile: an overhanging wedge whose top rises gently toward
    /// the screen.
    fn panel(&self) -> Vec<[f32; 2]> {
        let (hd, py, zp) = (self.hd, self.py, self.zp);
        vec![
            [hd - 0.13, py - 0.14],
            [hd, py - 0.035],
            [hd, py],
            [zp, py + 0.05],
            [zp, py - 0.14],
        ]
    }

    /// The screen housing's side profile: its front leaning back from the panel's back edge
    /// up to the marquee.
    fn screen_block(&self) -> Vec<[f32; 2]> {
        let (hd, py, zp, my) = (self.hd, self.py, self.zp, self.my);
        vec![
            [-hd, py - 0.14],
            [zp, py - 0.14],
            [zp, py + 0.05],
            [zp - 0.16, my],
            [-hd, my],
        ]
    }
}

/// The two side panels, each in three convex pieces that follow the cabinet's profile.
fn arcade_sides(b: &mut AssetBuilder, m: usize, s: &ArcadeProfile, hw: f32, t: f32) {
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = if sx < 0.0 {
            [-hw, -hw + t]
        } else {
            [hw - t, hw]
        };
        b.cuboid(
            &format!("side_{k}_low"),
            m,
            [x[0], 0.0, -s.hd],
            [x[1], s.py - 0.13, s.hd - 0.12],
        );
        let mid = [
            [-s.hd, s.py - 0.14],
            [s.hd - 0.13, s.py - 0.14],
            [s.hd + 0.005, s.py - 0.03],
            [s.hd + 0.005, s.py + 0.015],
            [-s.hd, s.py + 0.015],
        ];
        b.part(prism_x(&format!("side_{k}_mid"), m, &mid, x[0], x[1]));
        let upper = [
            [-s.hd, s.py],
            [s.zp + 0.03, s.py],
            [s.zp + 0.03, s.py + 0.07],
            [s.zp - 0.13, s.my],
            [-s.hd, s.my],
        ];
        b.part(prism_x(&format!("side_{k}_upper"), m, &upper, x[0], x[1]));
        b.cuboid(
            &format!("side_{k}_top"),
            m,
            [x[0], s.my - 0.001, -s.hd],
            [x[1], s.h, s.zp + 0.04],
        );
    }
}

/// The bezel and the picture on the leaning front of the screen housing.
fn arcade_screen(b: &mut AssetBuilder, [dark, screen]: [usize; 2], s: &ArcadeProfile, inner: f32) {
    let (p, q) = ([s.zp, s.py + 0.05], [s.zp - 0.16, s.my]);
    let len = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt();
    let ([z, y], tilt) = along_slope(p, q, 0.5 * len, 0.002);
    let rot = rotation([1.0, 0.0, 0.0], tilt);
    b.part(rotated_box(
        "bezel",
        dark,
        [0.0, y, z],
        [inner - 0.01, 0.004, 0.5 * len - 0.01],
        &rot,
    ));
    let ([z, y], _) = along_slope(p, q, 0.5 * len, 0.006);
    b.part(rotated_box(
        "screen",
        screen,
        [0.0, y, z],
        [
            0.75 * inner,
            0.001,
            (0.5 * len - 0.05).min(0.75 * inner * 0.75),
        ],
        &rot,
    ));
}

/// One or two joysticks with a cluster of buttons each on the control panel's top.
fn arcade_controls(
    b: &mut AssetBuilder,
    [dark, metal]: [usize; 2],
    s: &ArcadeProfile,
    inner: f32,
    rng: &mut ChaCha8Rng,
) {
    let buttons = b.material(crate::materials::pick_material(Palette::BrightPlastic, rng));
    let players = int(rng, 1, 2);
    let (p, q) = ([s.hd, s.py], [s.zp, s.py + 0.05]);
    let (_, tilt) = along_slope(p, q, 0.0, 0.0);
    let n = Vector3::new(0.0, tilt.cos(), tilt.sin());
    for pl in 0..players {
        let cx = if players == 1 {
            -0.12
        } else {
            [-0.75, 0.0][pl] * inner
        };
        let ([z, y], _) = along_slope(p, q, 0.13, 0.0);
        let base = Vector3::new(cx, y, z);
        b.part(tube(
            &format!("stick_{pl}"),
            metal,
            base.into(),
            (base + n * 0.07).into(),
            0.005,
            0.005,
            8,
        ));
        b.part(sphere(
            &format!("ball_top_{pl}"),
            buttons,
            (base + n * 0.08).into(),
            0.017,
            6,
            10,
        ));
        for k in 0..6 {
            let (col, row) = ((k % 3) as f32, (k / 3) as f32);
            let ([bz, by], _) = along_slope(p, q, 0.1 + 0.045 * row, 0.0);
            let c = Vector3::new(cx + 0.09 + 0.042 * col, by, bz);
            b.part(tube(
                &format!("button_{pl}_{k}"),
                if k % 2 == 0 { buttons } else { dark },
                (c - n * 0.002).into(),
                (c + n * 0.01).into(),
                0.014,
                0.014,
                12,
            ));
        }
    }
}

// --- table games ---

/// Foosball table (table football: box 1.36–1.52 long (x) × 0.72–0.78 wide, top 0.88–0.94 high,
/// 1.22–1.28 deep over its handles): four legs under an open playing box with a green field,
/// goals at both ends, eight rods across it (z) with handles out of the front (+Z) for one
/// team and out of the back for the other, and 1-2-3-5 players per team on them, in two
/// team colours.
pub(super) fn foosball_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let body = mat_either(&mut b, 0.6, Palette::Wood, Palette::PaintedWood, rng);
    let field = b.material(fixed_material("field", [0x2E, 0x7A, 0x3A], 0.7, 0.0));
    let white = b.material(fixed_material("line", [0xF0, 0xF0, 0xEC], 0.6, 0.0));
    let steel = b.material(fixed_material("rod", [0xC8, 0xCA, 0xCC], 0.25, 1.0));
    let grip = mat_either(&mut b, 0.6, Palette::Rubber, Palette::Wood, rng);
    let teams = pick_team_colours(&mut b, rng);
    let (l, wd) = (uniform(rng, 1.36, 1.52), uniform(rng, 0.72, 0.78));
    let h = uniform(rng, 0.88, 0.94);
    let (hl, hw, wall) = (0.5 * l, 0.5 * wd, 0.03);
    let yb = h - uniform(rng, 0.22, 0.26);
    let yf = yb + 0.04;
    for (i, (sx, sz)) in super::carcass::CORNERS.iter().enumerate() {
        let (x, z) = (sx * (hl - 0.08), sz * (hw - 0.08));
        b.cuboid(
            &format!("leg_{i}"),
            body,
            [x - 0.035, 0.0, z - 0.035],
            [x + 0.035, yb + 0.001, z + 0.035],
        );
    }
    b.cuboid("field", field, [-hl, yb, -hw], [hl, yf, hw]);
    b.cuboid(
        "centre_line",
        white,
        [-0.004, yf - 0.001, -hw + wall],
        [0.004, yf + 0.0005, hw - wall],
    );
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        b.cuboid(
            &format!("end_wall_{k}"),
            body,
            [sx * hl - wall * (1.0 + sx) * 0.5, yb, -hw],
            [sx * hl + wall * (1.0 - sx) * 0.5, h, hw],
        );
        b.cuboid(
            &format!("side_wall_{k}"),
            body,
            [-hl, yb, sx * hw - wall * (1.0 + sx) * 0.5],
            [hl, h, sx * hw + wall * (1.0 - sx) * 0.5],
        );
        let gx = sx * (hl - wall);
        b.cuboid(
            &format!("goal_{k}"),
            teams[2],
            [gx - 0.004, yf, -0.1],
            [gx + 0.004, yf + 0.08, 0.1],
        );
    }
    let rod_y = h - 0.06;
    foosball_rods(
        &mut b,
        [steel, grip, teams[0], teams[1]],
        [hl - wall, hw],
        [yf, rod_y],
        rng,
    );
    b.finish(Placement::Floor, [0.95, 1.05])
}

/// Two distinct team colours and a goal colour.
fn pick_team_colours(b: &mut AssetBuilder, rng: &mut ChaCha8Rng) -> [usize; 3] {
    const COLOURS: [(&str, [u8; 3]); 5] = [
        ("red_team", [0xC8, 0x28, 0x24]),
        ("blue_team", [0x24, 0x4C, 0xB0]),
        ("yellow_team", [0xEE, 0xC4, 0x20]),
        ("black_team", [0x20, 0x20, 0x22]),
        ("white_team", [0xEE, 0xEE, 0xEA]),
    ];
    let first = int(rng, 0, COLOURS.len() - 1);
    let second = (first + int(rng, 1, COLOURS.len() - 1)) % COLOURS.len();
    let a = b.material(fixed_material(COLOURS[first].0, COLOURS[first].1, 0.4, 0.0));
    let c = b.material(fixed_material(
        COLOURS[second].0,
        COLOURS[second].1,
        0.4,
        0.0,
    ));
    let goal = b.material(fixed_material("goal", [0x10, 0x10, 0x10], 0.8, 0.0));
    [a, c, goal]
}

/// The eight rods across the field (inner half length `half` = (x, z)), with their players
/// standing on the field at `y[0]` and hanging from the rods at `y[1]`, and handles: the
/// first team's rods (goalie, defence, midfield, attack) have theirs at +Z.
fn foosball_rods(
    b: &mut AssetBuilder,
    m: [usize; 4],
    half: [f32; 2],
    y: [f32; 2],
    rng: &mut ChaCha8Rng,
) {
    let [steel, grip, team_a, team_b] = m;
    let [hx, hw] = half;
    // From the −X goal: which team owns each rod, and its number of players.
    const RODS: [(bool, usize); 8] = [
        (true, 1),
        (true, 2),
        (false, 3),
        (true, 5),
        (false, 5),
        (true, 3),
        (false, 2),
        (false, 1),
    ];
    let out_short = uniform(rng, 0.04, 0.12);
    for (i, (team_a_rod, players)) in RODS.into_iter().enumerate() {
        let x = -hx + (i as f32 + 0.5) * 2.0 * hx / 8.0;
        let sz = if team_a_rod { 1.0 } else { -1.0 };
        let handle = sz * (hw + 0.25);
        b.part(rod(
            &format!("rod_{i}"),
            steel,
            [x, y[1], -sz * (hw + out_short)],
            [x, y[1], sz * (hw + 0.14)],
            0.008,
            0.008,
            8,
        ));
        b.part(rod(
            &format!("handle_{i}"),
            grip,
            [x, y[1], sz * (hw + 0.13)],
            [x, y[1], handle],
            0.017,
            0.017,
            10,
        ));
        let colour = if team_a_rod { team_a } else { team_b };
        let spacing = (2.0 * hw - 0.1) / players as f32;
        for p in 0..players {
            let z = -hw + 0.05 + (p as f32 + 0.5) * spacing;
            b.cuboid(
                &format!("player_{i}_{p}"),
                colour,
                [x - 0.011, y[0] + 0.012, z - 0.018],
                [x + 0.011, y[1] + 0.02, z + 0.018],
            );
            b.part(sphere(
                &format!("head_{i}_{p}"),
                colour,
                [x, y[1] + 0.037, z],
                0.016,
                6,
                10,
            ));
        }
    }
}

/// Ping-pong table (table tennis, to the ITTF size: top 2.74 × 1.525 at 0.76 high, 1.83 deep
/// over the net posts): two halves of a 19–25 mm top with white edge and centre lines, a
/// 15.25 cm net across the middle on clamped posts, an apron under the edges, and leg frames
/// with stretchers (sometimes on castors). Each half is a support surface.
pub(super) fn ping_pong_table(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let top_m = b.material(pick_table_colour(rng));
    let white = b.material(fixed_material("line", [0xF4, 0xF4, 0xF0], 0.6, 0.0));
    let frame = mat(&mut b, Palette::CoatedMetal, rng);
    let net = b.material(fixed_material("net", [0x1E, 0x22, 0x2A], 0.9, 0.0));
    let (hl, hw, top) = (1.37, 0.7625, 0.76);
    let t = uniform(rng, 0.019, 0.025);
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = if sx < 0.0 { [-hl, -0.003] } else { [0.003, hl] };
        b.cuboid(
            &format!("top_{k}"),
            top_m,
            [x[0], top - t, -hw],
            [x[1], top, hw],
        );
        table_lines(&mut b, white, &format!("{k}"), x, hw, top);
        b.cuboid(
            &format!("apron_{k}_front"),
            frame,
            [x[0] + 0.05, top - t - 0.06, hw - 0.06],
            [x[1] - 0.05, top - t + 0.001, hw - 0.04],
        );
        b.cuboid(
            &format!("apron_{k}_back"),
            frame,
            [x[0] + 0.05, top - t - 0.06, -hw + 0.04],
            [x[1] - 0.05, top - t + 0.001, -hw + 0.06],
        );
        let side = ["left", "right"][k];
        b.top_surface(
            &format!("top_{side}"),
            [x[0], -hw],
            [x[1], hw],
            top + 0.0004,
            0.05,
        );
    }
    table_legs(&mut b, frame, [hl, hw], top - t, coin(rng, 0.5));
    let post_z = hw + 0.1525;
    b.cuboid(
        "net",
        net,
        [-0.002, top + 0.004, -post_z],
        [0.002, top + 0.1525 - 0.015, post_z],
    );
    b.cuboid(
        "net_tape",
        white,
        [-0.003, top + 0.1525 - 0.015, -post_z],
        [0.003, top + 0.1525, post_z],
    );
    for (k, sz) in [-1.0f32, 1.0].into_iter().enumerate() {
        b.part(rod(
            &format!("net_post_{k}"),
            frame,
            [0.0, top - 0.01, sz * post_z],
            [0.0, top + 0.1525, sz * post_z],
            0.008,
            0.008,
            8,
        ));
        let z = if sz > 0.0 {
            [hw - 0.03, post_z + 0.01]
        } else {
            [-post_z - 0.01, -hw + 0.03]
        };
        b.cuboid(
            &format!("net_clamp_{k}"),
            frame,
            [-0.02, top - t - 0.025, z[0]],
            [0.02, top + 0.012, z[1]],
        );
    }
    b.finish(Placement::Floor, [0.98, 1.02])
}

/// A table tennis top colour: blue, green or black.
fn pick_table_colour(rng: &mut ChaCha8Rng) -> scenethesis_scene_graph::Material {
    let (name, rgb) = *pick(
        rng,
        &[
            ("blue_top", [0x1E, 0x4A, 0x8C]),
            ("blue_top", [0x24, 0x3E, 0x70]),
            ("green_top", [0x1E, 0x5E, 0x3A]),
            ("black_top", [0x1E, 0x20, 0x22]),
        ],
    );
    fixed_material(name, rgb, 0.5, 0.0)
}

/// The white lines on one half (x range `x`): side lines, the end line and the centre line,
/// 0.4 mm proud of the top.
fn table_lines(b: &mut AssetBuilder, white: usize, name: &str, x: [f32; 2], hw: f32, top: f32) {
    let y = [top - 0.001, top + 0.0004];
    b.cuboid(
        &format!("line_{name}_front"),
        white,
        [x[0], y[0], hw - 0.02],
        [x[1], y[1], hw],
    );
    b.cuboid(
        &format!("line_{name}_back"),
        white,
        [x[0], y[0], -hw],
        [x[1], y[1], -hw + 0.02],
    );
    let end = if x[0] < 0.0 {
        [x[0], x[0] + 0.02]
    } else {
        [x[1] - 0.02, x[1]]
    };
    b.cuboid(
        &format!("line_{name}_end"),
        white,
        [end[0], y[0], -hw],
        [end[1], y[1], hw],
    );
    b.cuboid(
        &format!("line_{name}_centre"),
        white,
        [x[0], y[0], -0.0015],
        [x[1], y[1], 0.0015],
    );
}

/// Four pairs of legs (each pair joined by a stretcher along z) under the top's underside at
/// `under`, inset from the corners of the half extents `half`, on castors or plain feet.
fn table_legs(b: &mut AssetBuilder, m: usize, half: [f32; 2], under: f32, castors: bool) {
    let [hl, hw] = half;
    let foot = if castors { 0.06 } else { 0.0 };
    for (i, x) in [-hl + 0.3, -0.3, 0.3, hl - 0.3].into_iter().enumerate() {
        for (k, z) in [-hw + 0.12, hw - 0.12].into_iter().enumerate() {
            b.cuboid(
                &format!("leg_{i}_{k}"),
                m,
                [x - 0.02, foot, z - 0.02],
                [x + 0.02, under + 0.001, z + 0.02],
            );
            if castors {
                b.part(ellipsoid(
                    &format!("castor_{i}_{k}"),
                    m,
                    [x, 0.03, z],
                    [0.012, 0.03, 0.03],
                    6,
                    10,
                ));
            }
        }
        b.cuboid(
            &format!("stretcher_{i}"),
            m,
            [x - 0.015, 0.2, -hw + 0.12],
            [x + 0.015, 0.23, hw - 0.12],
        );
    }
}

// --- dartboard ---

/// Dartboard (a regulation bristle board 0.451 across and 38 mm thick; wall-mounted): twenty
/// sectors in alternating black and cream with red and green double and treble rings, the
/// outer and inner bull, on a black rim. About half the seeds hang it in a wooden cabinet
/// (width 0.58–0.66, height 0.62–0.72, depth 0.095–0.11) closed by two doors hinged at its
/// sides (joints, closed = 0) with chalk scoreboards inside them; bare boards sometimes
/// have a foam surround ring.
pub(super) fn dartboard(rng: &mut ChaCha8Rng) -> Asset {
    let mut b = AssetBuilder::new();
    let colours = DartColours::new(&mut b);
    if coin(rng, 0.5) {
        let wood = mat(&mut b, Palette::Wood, rng);
        let handle = mat(&mut b, Palette::Metal, rng);
        let (w, h) = (uniform(rng, 0.58, 0.66), uniform(rng, 0.62, 0.72));
        let depth = uniform(rng, 0.095, 0.11);
        dart_cabinet(&mut b, [wood, handle, colours.black], [w, h, depth]);
        dart_board(&mut b, &colours, [0.0, 0.5 * h], 0.012);
    } else {
        let r = 0.2255;
        if coin(rng, 0.4) {
            let ring = b.material(crate::materials::pick_material(Palette::Rubber, rng));
            b.part(rod(
                "surround",
                ring,
                [0.0, 0.35, 0.0],
                [0.0, 0.35, 0.03],
                0.35,
                0.35,
                40,
            ));
            dart_board(&mut b, &colours, [0.0, 0.35], 0.005);
        } else {
            b.cuboid(
                "bracket",
                colours.black,
                [-0.04, r - 0.04, 0.0],
                [0.04, r + 0.04, 0.008],
            );
            dart_board(&mut b, &colours, [0.0, r], 0.007);
        }
    }
    b.finish(Placement::Wall, [1.0, 1.0])
}

/// The four colours of a board.
struct DartColours {
    black: usize,
    cream: usize,
    red: usize,
    green: usize,
}

impl DartColours {
    /// Registers the board's colours with the builder.
    fn new(b: &mut AssetBuilder) -> Self {
        Self {
            black: b.material(fixed_material("board_black", [0x1A, 0x1A, 0x1A], 0.9, 0.0)),
            cream: b.material(fixed_material("board_cream", [0xE8, 0xDC, 0xB8], 0.9, 0.0)),
            red: b.material(fixed_material("board_red", [0xC0, 0x22, 0x22], 0.8, 0.0)),
            green: b.material(fixed_material("board_green", [0x1E, 0x7A, 0x3A], 0.8, 0.0)),
        }
    }
}

/// The board centred at (x, y) = `at`, its back at z = `z0`: a black disc 0.451 across and
/// 38 mm thick, then the scoring rings (regulation radii) 2 mm proud of it, then the bulls.
fn dart_board(b: &mut AssetBuilder, c: &DartColours, at: [f32; 2], z0: f32) {
    let [x, y] = at;
    let face = z0 + 0.038;
    b.part(rod(
        "board",
        c.black,
        [x, y, z0],
        [x, y, face],
        0.2255,
        0.2255,
        40,
    ));
    // Built about +Y at the origin, then turned so +Y points out of the wall.
    let rot = rotation([1.0, 0.0, 0.0], FRAC_PI_2);
    let bands = [
        (0.0159, 0.099),
        (0.099, 0.107),
        (0.107, 0.162),
        (0.162, 0.17),
    ];
    let step = TAU / 20.0;
    for k in 0..20 {
        let a0 = -FRAC_PI_2 - 0.5 * step + k as f32 * step;
        for (band, (r0, r1)) in bands.into_iter().enumerate() {
            let m = match (band % 2 == 0, k % 2 == 0) {
                (true, true) => c.black,
                (true, false) => c.cream,
                (false, true) => c.red,
                (false, false) => c.green,
            };
            let part = ring_slab(
                &format!("sector_{k}_{band}"),
                m,
                [0.0, 0.0],
                a0,
                a0 + step,
                (r0, r1, face - 0.001),
                (r0, r1, face + 0.002),
            );
            b.part(transformed(part, &rot, [x, y, 0.0]));
        }
    }
    b.part(rod(
        "outer_bull",
        c.green,
        [x, y, face - 0.001],
        [x, y, face + 0.0025],
        0.0159,
        0.0159,
        16,
    ));
    b.part(rod(
        "bullseye",
        c.red,
        [x, y, face],
        [x, y, face + 0.003],
        0.00635,
        0.00635,
        12,
    ));
}

/// The cabinet round a board, `size` = (width, height, depth): a back board, sides, top and
/// bottom, and two doors meeting in the middle, each with a chalk scoreboard on its inside.
fn dart_cabinet(b: &mut AssetBuilder, [wood, handle, chalk]: [usize; 3], size: [f32; 3]) {
    let [w, h, depth] = size;
    let (hw, t, door_t) = (0.5 * w, 0.018, 0.018);
    let zf = depth - door_t;
    b.cuboid("back", wood, [-hw, 0.0, 0.0], [hw, h, 0.012]);
    for (k, sx) in [-1.0f32, 1.0].into_iter().enumerate() {
        let x = if sx < 0.0 {
            [-hw, -hw + t]
        } else {
            [hw - t, hw]
        };
        b.cuboid(&format!("side_{k}"), wood, [x[0], 0.0, 0.0], [x[1], h, zf]);
    }
    b.cuboid(
        "bottom",
        wood,
        [-hw + t - 0.001, 0.0, 0.0],
        [hw - t + 0.001, t, zf],
    );
    b.cuboid(
        "top",
        wood,
        [-hw + t - 0.001, h - t, 0.0],
        [hw - t + 0.001, h, zf],
    );
    let m = LinkMaterials {
        panel: wood,
        handle,
    };
    for (name, x, hinge_left) in [
        ("door_left", [-hw, -0.0015], true),
        ("door_right", [0.0015, hw], false),
    ] {
        articulation::door(
            b,
            name,
            m,
            Leaf {
                x,
                y: [0.0, h],
                z: zf,
                thickness: door_t,
                hinge_left,
            },
        );
        b.link(Some(name));
        b.cuboid(
            &format!("{name}_scoreboard"),
            chalk,
            [x[0] + 0.04, 0.15 * h, zf - 0.004],
            [x[1] - 0.04, 0.85 * h, zf + 0.001],
        );
        b.link(None);
    }
}
