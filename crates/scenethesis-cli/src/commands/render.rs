//! `scenethesis render`: preview images of an output folder (photo, top and orbit views).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::Arc;

use anyhow::{Context, Result};
use scenethesis_imagery::{encode_png, Camera};
use scenethesis_import::AssetResolver;
use scenethesis_procedural::catalog;
use scenethesis_render::{
    labels, views, BackendChoice, Instance, PreparedScene, RenderScene, Renderer, RendererOptions,
};
use scenethesis_scene_graph::{write_file_atomic, Architecture, Mesh, Scene};

/// An image size written `WIDTHxHEIGHT`, e.g. `800x600`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Size {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl FromStr for Size {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let bad = || format!("`{s}` is not a size: expected WIDTHxHEIGHT, e.g. 800x600");
        let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
        let width: u32 = w.trim().parse().map_err(|_| bad())?;
        let height: u32 = h.trim().parse().map_err(|_| bad())?;
        if width == 0 || height == 0 || width > 8192 || height > 8192 {
            return Err(format!(
                "`{s}`: width and height must be between 1 and 8192"
            ));
        }
        Ok(Self { width, height })
    }
}

/// Arguments of `scenethesis render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// Output folder holding scene.json (or the scene.json itself); images are written next to it.
    pub dir: PathBuf,
    /// Number of views around the scene (view_0.png …).
    #[arg(long, default_value_t = 4)]
    pub views: usize,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, default_value = "800x600")]
    pub size: Size,
    /// Graphics backend: auto, gl or vulkan (default: `WGPU_BACKEND`, else auto).
    #[arg(long)]
    pub backend: Option<BackendChoice>,
    /// Also write metric depth (NAME_depth.npy, float32 metres along the optical axis).
    #[arg(long)]
    pub depth: bool,
    /// Render colour at this many times the size per side and average down (anti-aliasing).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=4))]
    pub supersample: u32,
    /// Instead of previews, write what the vision guide reads for the photo view into
    /// DIR/guidance/: rgb.png, depth.npy (metres), ids.png + labels.json and camera.json.
    #[arg(long)]
    pub guidance: bool,
}

/// Renders the folder's previews: `preview.png` (photo view), `preview_top.png` and
/// `view_K.png` for K in 0..views.
pub fn run(args: RenderArgs) -> Result<()> {
    let (dir, file) = if args.dir.is_dir() {
        (args.dir.clone(), args.dir.join("scene.json"))
    } else {
        let parent = args.dir.parent().map(Path::to_path_buf).unwrap_or_default();
        (parent, args.dir.clone())
    };
    let scene = Scene::read_json(&file).context("cannot render")?;
    if args.guidance {
        return write_guidance(&scene, &file, &dir, &args);
    }
    let (render_scene, skipped) = render_scene(&scene);
    if !skipped.is_empty() {
        // Previews that leave objects out would silently replace correct ones: refuse.
        for reason in &skipped {
            eprintln!("  - {reason}");
        }
        anyhow::bail!(
            "cannot render {}: {} object(s) have no mesh (listed above); previews left unchanged",
            file.display(),
            skipped.len()
        );
    }
    let renderer = open_renderer(args.backend)?;
    let prepared = renderer
        .prepare(&render_scene)
        .with_context(|| format!("cannot render {}", file.display()))?;
    let (w, h) = (args.size.width, args.size.height);
    let mut shots: Vec<(String, Camera)> = vec![
        ("preview".into(), views::photo_view(&render_scene, w, h)),
        ("preview_top".into(), views::top_view(&render_scene, w, h)),
    ];
    for (k, camera) in views::orbit_views(&render_scene, args.views, w, h)
        .into_iter()
        .enumerate()
    {
        shots.push((format!("view_{k}"), camera));
    }
    println!(
        "rendering {} of {} objects on {}",
        render_scene.instances.len(),
        scene.objects.len(),
        renderer.adapter_description()
    );
    for (name, camera) in &shots {
        let plan = (name == "preview_top").then_some(&scene.architecture);
        write_view(&renderer, &prepared, (camera, plan), &dir, name, &args)?;
    }
    Ok(())
}

/// Renders view `name` from `camera` into `dir` (colour, and depth when asked), labelled with
/// the rooms of `plan` when given (a house's top view).
fn write_view(
    renderer: &Renderer,
    prepared: &PreparedScene,
    (camera, plan): (&Camera, Option<&Architecture>),
    dir: &Path,
    name: &str,
    args: &RenderArgs,
) -> Result<()> {
    let mut color = renderer
        .render_color_supersampled(prepared, camera, args.supersample)
        .with_context(|| format!("rendering {name} failed"))?;
    if let Some(plan) = plan {
        labels::label_rooms(&mut color, camera, plan);
    }
    let png = encode_png(&color).with_context(|| format!("encoding {name}.png"))?;
    let path = dir.join(format!("{name}.png"));
    write_file_atomic(&path, &png).with_context(|| format!("cannot write {}", path.display()))?;
    println!("wrote {}", path.display());
    if args.depth {
        let frame = renderer
            .render_prepared(prepared, camera)
            .with_context(|| format!("rendering depth of {name} failed"))?;
        let path = dir.join(format!("{name}_depth.npy"));
        write_file_atomic(
            &path,
            &scenethesis_vision::files::write_npy(
                frame.width(),
                frame.height(),
                frame.depth.values(),
            ),
        )
        .with_context(|| format!("cannot write {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Writes the photo view's guidance files into `dir/guidance/`.
fn write_guidance(scene: &Scene, file: &Path, dir: &Path, args: &RenderArgs) -> Result<()> {
    let meshes = scenethesis_pipeline::resolve_meshes(
        scene,
        &scenethesis_pipeline::RetrievalSource::default(),
    )
    .with_context(|| format!("cannot rebuild the meshes of {}", file.display()))?;
    let renderer = open_renderer(args.backend)?;
    let guidance = renderer
        .render_guidance(scene, &meshes, [args.size.width, args.size.height])
        .with_context(|| format!("cannot render the guidance of {}", file.display()))?;
    let labels = scenethesis_vision::files::scene_labels(scene);
    let out = dir.join("guidance");
    std::fs::create_dir_all(&out).with_context(|| format!("cannot write {}", out.display()))?;
    for (name, bytes) in scenethesis_vision::files::encode_guidance(&guidance, &labels)? {
        let path = out.join(name);
        write_file_atomic(&path, &bytes)
            .with_context(|| format!("cannot write {}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Opens the renderer for `backend` (default: `WGPU_BACKEND`, else the fastest adapter).
pub fn open_renderer(backend: Option<BackendChoice>) -> Result<Renderer> {
    let options = match backend {
        Some(backend) => RendererOptions {
            backend,
            ..RendererOptions::default()
        },
        None => RendererOptions::from_env()?,
    };
    Renderer::new(options).context("cannot render")
}

/// The scene's objects with their meshes (procedural assets regenerated, imported assets
/// imported again from their asset folder, both through
/// [`scenethesis_import::AssetResolver`]), in the scene's architecture; objects whose
/// mesh cannot be made (unknown generators, missing asset files) are left out, each with a
/// message naming it.
pub fn render_scene(scene: &Scene) -> (RenderScene, Vec<String>) {
    let mut resolver = AssetResolver::new();
    let mut by_asset: BTreeMap<String, Arc<Mesh>> = BTreeMap::new();
    let mut by_object: BTreeMap<String, Arc<Mesh>> = BTreeMap::new();
    let mut skipped = Vec::new();
    for object in &scene.objects {
        let key = object.asset.to_string();
        let mesh = match by_asset.get(&key) {
            Some(mesh) => mesh.clone(),
            None => match resolver.mesh(&object.asset) {
                Ok(mesh) => {
                    let mesh = Arc::new(mesh);
                    by_asset.insert(key, mesh.clone());
                    mesh
                }
                Err(e) => {
                    skipped.push(format!(
                        "object `{}`: {e}",
                        scenethesis_scene_graph::printable(&object.id)
                    ));
                    continue;
                }
            },
        };
        by_object.insert(object.id.clone(), mesh);
    }
    (RenderScene::from_scene(scene, &by_object), skipped)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_sizes() {
        assert_eq!(
            "800x600".parse::<Size>().unwrap(),
            Size {
                width: 800,
                height: 600
            }
        );
        assert!("800".parse::<Size>().is_err());
        assert!("0x10".parse::<Size>().is_err());
        assert!("axb".parse::<Size>().unwrap_err().contains("WIDTHxHEIGHT"));
    }
}

/// Arguments of `scenethesis assets sheet`.
#[derive(Debug, clap::Args)]
pub struct SheetArgs {
    /// A built-in category, e.g. `bookshelf` (`scenethesis assets list` names them).
    pub category: String,
    /// The PNG file to write.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Number of seeds to show (seeds 0 … N−1).
    #[arg(long, default_value_t = 9)]
    pub seeds: u64,
    /// Size of one cell, WIDTHxHEIGHT.
    #[arg(long, default_value = "256x256")]
    pub cell: Size,
    /// Graphics backend: auto, gl or vulkan (default: `WGPU_BACKEND`, else auto).
    #[arg(long)]
    pub backend: Option<BackendChoice>,
}

/// Writes a contact sheet: one photo-view render per seed of a category on a neutral floor,
/// in a grid, each cell labelled with its seed.
pub fn run_sheet(args: SheetArgs) -> Result<()> {
    let category = catalog::category(&args.category).with_context(|| {
        let names: Vec<&str> = catalog::categories().map(|c| c.name).collect();
        format!(
            "unknown category `{}`; built-in categories: {}",
            args.category,
            names.join(", ")
        )
    })?;
    anyhow::ensure!(
        (1..=256).contains(&args.seeds),
        "--seeds must be between 1 and 256"
    );
    let renderer = open_renderer(args.backend)?;
    let sheet = contact_sheet(&renderer, category, args.seeds, args.cell)?;
    let png = encode_png(&sheet).context("encoding the contact sheet as PNG")?;
    write_file_atomic(&args.output, &png)
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    println!(
        "wrote {} ({} seeds of {}, {}×{})",
        args.output.display(),
        args.seeds,
        category.name,
        sheet.width(),
        sheet.height()
    );
    Ok(())
}

/// The contact sheet image of `seeds` seeds of `category`, `cell` pixels per seed.
pub fn contact_sheet(
    renderer: &Renderer,
    category: &catalog::Category,
    seeds: u64,
    cell: Size,
) -> Result<image::RgbaImage> {
    let columns = (seeds as f64).sqrt().ceil().max(1.0) as u32;
    let rows = (seeds as u32).div_ceil(columns);
    let mut sheet = image::RgbaImage::from_pixel(
        columns * cell.width,
        rows * cell.height,
        image::Rgba([255, 255, 255, 255]),
    );
    for seed in 0..seeds {
        let asset = catalog::generate(category, seed);
        let scene = RenderScene::studio(vec![Instance::new(
            category.name,
            Arc::new(asset.mesh),
            scenethesis_scene_graph::Pose::IDENTITY,
        )]);
        let camera = views::photo_view(&scene, cell.width, cell.height);
        let prepared = renderer.prepare(&scene)?;
        let image = renderer.render_color_supersampled(&prepared, &camera, 2)?;
        let (x0, y0) = (
            (seed as u32 % columns) * cell.width,
            (seed as u32 / columns) * cell.height,
        );
        image::imageops::replace(&mut sheet, &image, x0 as i64, y0 as i64);
        draw_label(&mut sheet, x0 + 4, y0 + 4, &seed.to_string());
    }
    Ok(sheet)
}

/// 3 × 5 bitmaps of the digits 0–9, one row per `u8` (bit 2 = left column).
const DIGITS: [[u8; 5]; 10] = [
    [7, 5, 5, 5, 7],
    [2, 6, 2, 2, 7],
    [7, 1, 7, 4, 7],
    [7, 1, 7, 1, 7],
    [5, 5, 7, 1, 1],
    [7, 4, 7, 1, 7],
    [7, 4, 7, 5, 7],
    [7, 1, 1, 1, 1],
    [7, 5, 7, 5, 7],
    [7, 5, 7, 1, 7],
];

/// Draws a number in a small white box at (x, y), three pixels per font pixel.
fn draw_label(image: &mut image::RgbaImage, x: u32, y: u32, digits: &str) {
    const SCALE: u32 = 3;
    let width = digits.len() as u32 * 4 * SCALE + SCALE;
    let height = 7 * SCALE;
    let mut put = |px: u32, py: u32, color: [u8; 4]| {
        if px < image.width() && py < image.height() {
            image.put_pixel(px, py, image::Rgba(color));
        }
    };
    for dy in 0..height {
        for dx in 0..width {
            put(x + dx, y + dy, [255, 255, 255, 255]);
        }
    }
    for (i, ch) in digits.chars().enumerate() {
        let Some(glyph) = ch.to_digit(10).map(|d| DIGITS[d as usize]) else {
            continue;
        };
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..3u32 {
                if bits & (4 >> col) != 0 {
                    for sy in 0..SCALE {
                        for sx in 0..SCALE {
                            put(
                                x + SCALE + (i as u32 * 4 + col) * SCALE + sx,
                                y + SCALE + row as u32 * SCALE + sy,
                                [30, 30, 30, 255],
                            );
                        }
                    }
                }
            }
        }
    }
}
