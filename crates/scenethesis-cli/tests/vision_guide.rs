//! `scenethesis generate --guide vision` end to end: from the guidance files `render --guidance`
//! writes for a generated scene, and online — an image server on 127.0.0.1 answers the edit of
//! the empty room with that real render and a VLM endpoint answers the objects' boxes — so the
//! whole path runs without a network. Bad guidance stops the run with one error naming the file,
//! and nothing is written.

use std::path::{Path, PathBuf};
use std::process::Output;
use std::sync::OnceLock;

use scenethesis_models::ImageData;
use scenethesis_openai::testing::{openai_completion, openai_image, Reply, TestServer};
use scenethesis_scene_graph::{recovery_errors, Scene};
use serde_json::{json, Value};

mod common;
use common::text;

const PROMPT: &str = "a bedroom with a bed, a nightstand and a wardrobe";
const KEY: &str = "sk-test-vision-guide-never-print-me";

fn scenethesis(args: &[&str]) -> Output {
    common::scenethesis_with_key(Some(KEY), args)
}

/// A scene generated offline and its guidance rendered at the vision guide's edit size
/// (768 × 512), shared by the tests: `(folder, guidance folder)`.
fn base() -> &'static (PathBuf, PathBuf) {
    static BASE: OnceLock<(PathBuf, PathBuf)> = OnceLock::new();
    BASE.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap().keep();
        let scene = dir.join("scene");
        let s = scene.to_str().unwrap();
        let out = scenethesis(&[
            "generate",
            PROMPT,
            "--out",
            s,
            "--no-preview",
            "--max-replans",
            "0",
        ]);
        assert!(out.status.success(), "{}", text(&out));
        let out = scenethesis(&["render", s, "--guidance", "--size", "768x512"]);
        assert!(out.status.success(), "{}", text(&out));
        (scene.clone(), scene.join("guidance"))
    })
}

fn objects(dir: &Path) -> serde_json::Map<String, Value> {
    let scene: Value =
        serde_json::from_slice(&std::fs::read(dir.join("scene.json")).unwrap()).unwrap();
    scene["objects"].as_object().unwrap().clone()
}

fn translation(o: &Value) -> [f64; 3] {
    let t = &o["pose"]["translation"];
    [0, 1, 2].map(|i| t[i].as_f64().unwrap())
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn report(dir: &Path) -> Value {
    serde_json::from_slice(&std::fs::read(dir.join("report.json")).unwrap()).unwrap()
}

#[test]
fn generate_from_given_guidance_files_recovers_the_rendered_scene() {
    let (scene, g) = base();
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("vision");
    let p = |n: &str| g.join(n).to_string_lossy().into_owned();
    let out = scenethesis(&[
        "generate",
        PROMPT,
        "--out",
        out_dir.to_str().unwrap(),
        "--no-preview",
        "--max-replans",
        "0",
        "--guide-image",
        &p("rgb.png"),
        "--guide-masks",
        &p("ids.png"),
        "--guide-labels",
        &p("labels.json"),
        "--guide-depth",
        &p("depth.npy"),
        "--camera",
        &p("camera.json"),
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let report = report(&out_dir);
    assert_eq!(report["guide"], "vision");
    assert_eq!(
        report["matcher"], "shape",
        "the default matcher aligned the objects"
    );
    let truth = objects(scene);
    let got = objects(&out_dir);
    assert!(got.len() >= 8, "only {} objects recovered", got.len());
    let mut errors: Vec<f64> = got
        .iter()
        .map(|(id, o)| distance(translation(o), translation(&truth[id])))
        .collect();
    errors.sort_by(|a, b| a.total_cmp(b));
    let median = errors[errors.len() / 2];
    assert!(
        median < 0.05,
        "median translation error {median} m: {errors:?}"
    );
    for (id, o) in &got {
        assert_eq!(o["parent"], truth[id]["parent"], "{id}'s parent");
    }
    // Every planned object is placed or reported, never invented.
    let dropped: Vec<&str> = report["guide_dropped"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["id"].as_str().unwrap())
        .collect();
    for id in truth.keys() {
        assert!(
            got.contains_key(id) || dropped.contains(&id.as_str()),
            "{id} is neither placed nor reported"
        );
    }
}

/// The scene rendered from the camera the vision guide renders the empty room with (the photo
/// view framing the room alone; the scene's own photo view frames its tall objects too): the
/// PNG the image server answers the edit with, and the VLM's answer — each object's box read
/// off the render's instance buffer (the test plays the model).
fn furnished_render(scene_dir: &Path) -> (Vec<u8>, Value) {
    use scenethesis_render::{views, RenderScene, Renderer};
    let scene = scenethesis_scene_graph::Scene::read_json(&scene_dir.join("scene.json")).unwrap();
    let meshes = scenethesis_pipeline::resolve_meshes(
        &scene,
        &scenethesis_pipeline::RetrievalSource::default(),
    )
    .unwrap();
    let [w, h] = [768u32, 512];
    let no_meshes = std::collections::BTreeMap::<String, scenethesis_scene_graph::Mesh>::new();
    let empty = RenderScene::from_scene(&scene, &no_meshes);
    let camera = views::photo_view(&empty, w, h);
    let full = RenderScene::from_scene(&scene, &meshes);
    let renderer = Renderer::from_env().unwrap();
    let frame = renderer
        .render_prepared(&renderer.prepare(&full).unwrap(), &camera)
        .unwrap();
    let png = scenethesis_imagery::RgbImage::from_rgba(&frame.color).to_png();
    let mut out = Vec::new();
    for o in &scene.objects {
        let Some(index) = frame.index_of(&o.id) else {
            continue;
        };
        let mut b = [u32::MAX, u32::MAX, 0, 0];
        for (i, &v) in frame.instance.iter().enumerate() {
            if v == index {
                let (x, y) = (i as u32 % w, i as u32 / w);
                b = [b[0].min(x), b[1].min(y), b[2].max(x + 1), b[3].max(y + 1)];
            }
        }
        if b[2] > b[0] {
            out.push(json!({"id": o.id, "box": [
                b[0] as f64 / w as f64, b[1] as f64 / h as f64,
                b[2] as f64 / w as f64, b[3] as f64 / h as f64]}));
        }
    }
    (png, json!({ "objects": out }))
}

/// The loopback image + VLM server of the online tests: `/images/edits` answers with `render`
/// (the furnished room), a chat asking for `object_supports` gets the model's (wrong) claim that
/// the bed stands on the wardrobe, any other chat gets `boxes`.
fn vision_server(scene: &Path, render: Vec<u8>, boxes: &Value) -> TestServer {
    let edited = ImageData::from_bytes(render, "the furnished render").unwrap();
    let answer = boxes.to_string();
    let supports = bed_on_wardrobe(scene);
    let server = TestServer::start(move |_, request| {
        if request.path.ends_with("/images/edits") {
            Reply::json(200, &openai_image(&edited))
        } else if request.path.ends_with("/chat/completions") {
            let asks_supports = request.body.windows(15).any(|w| w == b"object_supports");
            let content = if asks_supports { &supports } else { &answer };
            Reply::json(200, &openai_completion("eyes-1", content))
        } else {
            Reply::json(404, &json!({"error": {"message": "no such endpoint"}}))
        }
    });
    server
}

#[test]
fn generate_online_edits_the_empty_room_and_lifts_the_vlm_boxes() {
    let (scene, _) = base();
    let (render, boxes) = furnished_render(scene);
    let server = vision_server(scene, render.clone(), &boxes);
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("online");
    let out = scenethesis(&[
        "generate",
        PROMPT,
        "--out",
        out_dir.to_str().unwrap(),
        "--no-preview",
        "--max-replans",
        "0",
        "--guide",
        "vision",
        "--base-url",
        &server.base_url,
        "--image-model",
        "painter-1",
        "--vlm-model",
        "eyes-1",
    ]);
    assert!(out.status.success(), "{}", text(&out));
    assert!(!text(&out).contains(KEY), "the key must never be printed");
    let requests = server.requests();
    let edits: Vec<_> = requests
        .iter()
        .filter(|r| r.path.ends_with("/images/edits"))
        .collect();
    assert_eq!(edits.len(), 1, "one edit of the empty room");
    let body = &edits[0].body;
    let has = |needle: &[u8]| body.windows(needle.len()).any(|w| w == needle);
    assert!(has(b"painter-1") && has(b"Furnish this empty room") && has(b"\x89PNG"));
    let chats: Vec<_> = requests
        .iter()
        .filter(|r| r.path.ends_with("/chat/completions"))
        .collect();
    assert_eq!(
        chats.len(),
        2,
        "one VLM request for the boxes, one for the supports"
    );
    assert!(chats[1].json().to_string().contains("object_supports"));
    let chat = chats[0].json();
    assert_eq!(chat["model"], "eyes-1");
    let sent = chat.to_string();
    assert!(
        sent.contains(&format!(
            "data:image/png;base64,{}",
            &edited_b64(&render)[..64]
        )),
        "the VLM sees the edited image"
    );
    let report = report(&out_dir);
    assert_eq!(report["guide"], "vision");
    let models: Vec<String> = report["providers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.to_string())
        .collect();
    assert!(models.iter().any(|m| m.contains("painter-1")), "{models:?}");
    assert!(models.iter().any(|m| m.contains("eyes-1")), "{models:?}");
    // The model put the bed on the wardrobe: geometry plainly has it on the floor, so it stays
    // there and the disagreement is in the report's notes.
    let notes = report["notes"].to_string();
    let bed = truth_id(scene, "bed");
    assert!(
        notes.contains(&format!("support of `{bed}`: the model says `on "))
            && notes.contains("the geometry is kept"),
        "{notes}"
    );
    // Without depth the boxes are placed by metrology under the render's camera: the large
    // floor objects land near where the render shows them.
    let truth = objects(scene);
    let got = objects(&out_dir);
    for category in ["bed", "wardrobe"] {
        let (id, o) = got
            .iter()
            .find(|(_, o)| o["category"] == category)
            .unwrap_or_else(|| panic!("no {category} recovered: {:?}", got.keys()));
        let d = distance(translation(o), translation(&truth[id]));
        assert!(d < 0.5, "{id} is {d} m from where the render shows it");
    }
}

/// With --llm-cache the image model's edit is recorded with the VLM's answer: once the server
/// is gone, a replay from the cache alone gives the same scene byte for byte.
#[test]
fn generate_online_replays_the_image_edit_from_the_cache() {
    let (scene, _) = base();
    let (render, boxes) = furnished_render(scene);
    let server = vision_server(scene, render, &boxes);
    let base_url = server.base_url.clone();
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let run = |out: &Path, extra: &[&str]| {
        let mut args = vec![
            "generate",
            PROMPT,
            "--out",
            out.to_str().unwrap(),
            "--no-preview",
            "--max-replans",
            "0",
            "--guide",
            "vision",
            "--base-url",
            &base_url,
            "--image-model",
            "painter-1",
            "--vlm-model",
            "eyes-1",
            "--llm-cache",
            cache.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        scenethesis(&args)
    };
    let first = dir.path().join("first");
    let out = run(&first, &[]);
    assert!(out.status.success(), "{}", text(&out));
    let requests = server.requests();
    assert!(requests.iter().any(|r| r.path.ends_with("/images/edits")));
    drop(server);
    // The edit is recorded under its model and its input's digest, not with the input itself.
    let records: Vec<String> = std::fs::read_dir(&cache)
        .unwrap()
        .map(|e| std::fs::read_to_string(e.unwrap().path()).unwrap())
        .collect();
    let edit = records
        .iter()
        .find(|r| r.contains("\"operation\":\"image-edit\""))
        .expect("the image edit is in the cache");
    assert!(
        edit.contains("painter-1") && edit.contains("\"sha256\":"),
        "{}",
        &edit[..300.min(edit.len())]
    );
    let second = dir.path().join("second");
    let out = run(&second, &["--llm-replay"]);
    assert!(
        out.status.success(),
        "replay without the server: {}",
        text(&out)
    );
    let a = std::fs::read(first.join("scene.json")).unwrap();
    let b = std::fs::read(second.join("scene.json")).unwrap();
    assert!(a == b, "the replay gives the same scene.json");
    // Without the edit in the cache the replay cannot furnish the room: a clear miss.
    for r in std::fs::read_dir(&cache).unwrap() {
        let path = r.unwrap().path();
        if std::fs::read_to_string(&path)
            .unwrap()
            .contains("\"operation\":\"image-edit\"")
        {
            std::fs::remove_file(path).unwrap();
        }
    }
    let out = run(&dir.path().join("third"), &["--llm-replay"]);
    assert!(!out.status.success(), "a replay missing the edit fails");
    assert!(!dir.path().join("third").exists(), "nothing is written");
}

fn truth_id(scene_dir: &Path, category: &str) -> String {
    objects(scene_dir)
        .into_iter()
        .find(|(_, o)| o["category"] == category)
        .map(|(id, _)| id)
        .unwrap_or_else(|| panic!("no {category} in the scene"))
}

/// A VLM answer on the supports: every object on the floor but the bed, which it puts on the
/// wardrobe (impossible for the lifted boxes).
fn bed_on_wardrobe(scene_dir: &Path) -> String {
    let supports: Vec<Value> = objects(scene_dir)
        .iter()
        .map(|(id, o)| {
            if o["category"] == "bed" {
                json!({"id": id, "relation": "on", "parent": truth_id(scene_dir, "wardrobe")})
            } else {
                json!({"id": id, "relation": "floor", "parent": ""})
            }
        })
        .collect();
    json!({ "supports": supports }).to_string()
}

fn edited_b64(bytes: &[u8]) -> String {
    ImageData::from_bytes(bytes.to_vec(), "png")
        .unwrap()
        .to_base64()
}

/// A copy of the rendered guidance folder to break.
fn copy_guidance(to: &Path) -> PathBuf {
    let (_, g) = base();
    let dst = to.join("g");
    std::fs::create_dir_all(&dst).unwrap();
    for f in [
        "rgb.png",
        "ids.png",
        "labels.json",
        "depth.npy",
        "camera.json",
    ] {
        std::fs::copy(g.join(f), dst.join(f)).unwrap();
    }
    dst
}

/// The flags that hand `generate` the guidance folder `g`'s files.
fn guide_flags(g: &Path) -> Vec<String> {
    let mut flags = Vec::new();
    for (flag, file) in [
        ("--guide-image", "rgb.png"),
        ("--guide-masks", "ids.png"),
        ("--guide-labels", "labels.json"),
        ("--guide-depth", "depth.npy"),
        ("--camera", "camera.json"),
    ] {
        flags.push(flag.to_owned());
        flags.push(g.join(file).to_string_lossy().into_owned());
    }
    flags
}

/// `scenethesis` with `args` and then the guide flags of `g`.
fn with_guidance(args: &[&str], g: &Path) -> Output {
    let flags = guide_flags(g);
    let all: Vec<&str> = args
        .iter()
        .copied()
        .chain(flags.iter().map(String::as_str))
        .collect();
    scenethesis(&all)
}

fn generate_with(g: &Path, out: &Path) -> Output {
    let out = out.to_str().unwrap();
    with_guidance(&["generate", PROMPT, "--out", out, "--no-preview"], g)
}

#[test]
fn bad_guidance_gets_one_clear_error_and_nothing_is_written() {
    type Break = fn(&Path);
    let cases: [(&str, Break, &[&str]); 4] = [
        (
            "image of the wrong size",
            |g| {
                image::RgbImage::new(320, 240)
                    .save(g.join("rgb.png"))
                    .unwrap()
            },
            &["rgb.png", "320 × 240", "768 × 512"],
        ),
        (
            "masks not matching the image",
            |g| {
                image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::new(100, 50)
                    .save(g.join("ids.png"))
                    .unwrap()
            },
            &["ids.png", "100 × 50"],
        ),
        (
            "NaN depth",
            |g| {
                let mut v = vec![1.5f32; 768 * 512];
                v[768 * 2 + 5] = f32::NAN;
                std::fs::write(
                    g.join("depth.npy"),
                    scenethesis_vision::files::write_npy(768, 512, &v),
                )
                .unwrap()
            },
            &["depth.npy", "pixel (5, 2)"],
        ),
        (
            "a camera looking at the ceiling",
            |g| {
                let path = g.join("camera.json");
                let mut c: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
                // Turn the camera half a turn about its own x axis: it now looks up.
                let q = &c["rotation"];
                let [x, y, z, w] = [0, 1, 2, 3].map(|i| q[i].as_f64().unwrap());
                let r = [w, z, -y, -x]; // q * (1, 0, 0, 0) as [i, j, k, w]
                c["rotation"] = json!(r);
                std::fs::write(&path, c.to_string()).unwrap()
            },
            &["camera.json", "looking down at the floor"],
        ),
    ];
    for (what, break_it, needles) in cases {
        let dir = tempfile::tempdir().unwrap();
        let g = copy_guidance(dir.path());
        break_it(&g);
        let out_dir = dir.path().join("out");
        let out = generate_with(&g, &out_dir);
        let t = text(&out);
        assert!(!out.status.success(), "{what}: accepted\n{t}");
        for n in needles {
            assert!(t.contains(n), "{what}: the error does not say `{n}`:\n{t}");
        }
        assert!(!t.contains("✔ plan"), "{what}: the run started:\n{t}");
        assert!(!out_dir.exists(), "{what}: something was written");
    }
}

/// The image leads: guidance rendered from scene A and a generic prompt whose plan differs.
/// Every labelled object of A is matched to a planned object of its category or adopted into
/// the plan, and lands where the image shows it; a label whose category the library cannot
/// map is reported with the nearest category, and a planned object the image does not show is
/// never invented.
#[test]
fn a_generic_prompt_adopts_what_the_image_shows() {
    let (scene, _) = base();
    let dir = tempfile::tempdir().unwrap();
    let g = copy_guidance(dir.path());
    // An extra label the image does not show, naming no category of the library.
    let path = g.join("labels.json");
    let mut labels: Value = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    labels["999"] = json!({"id": "hovercraft_0", "category": "hovercraft"});
    std::fs::write(&path, labels.to_string()).unwrap();
    let out_dir = dir.path().join("generic");
    let p = |n: &str| g.join(n).to_string_lossy().into_owned();
    let out = scenethesis(&[
        "generate",
        "a bedroom",
        "--out",
        out_dir.to_str().unwrap(),
        "--no-preview",
        "--max-replans",
        "0",
        "--guide-image",
        &p("rgb.png"),
        "--guide-masks",
        &p("ids.png"),
        "--guide-labels",
        &p("labels.json"),
        "--guide-depth",
        &p("depth.npy"),
        "--camera",
        &p("camera.json"),
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let report = report(&out_dir);
    let adopted = report["guide_adopted"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    assert!(
        !adopted.is_empty(),
        "the generic plan lacks some of A's objects: {report}"
    );
    let unmapped = &report["guide_unmapped"];
    assert_eq!(unmapped[0]["id"], "hovercraft_0", "{unmapped}");
    assert!(unmapped[0]["nearest"].is_string(), "{unmapped}");
    let truth = scene_of(scene);
    let labelled = visible_labels(&base().1);
    let got = scene_of(&out_dir);
    let errors = recovery_errors(&truth, &labelled, &got);
    let within = errors.iter().filter(|e| **e < 0.10).count();
    let share = within as f64 / labelled.len() as f64;
    let mut sorted = errors.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    assert!(
        share >= 0.85 && median < 0.03,
        "{within} of {} labelled objects within 10 cm, median {median:.3} m: {errors:?}",
        labelled.len()
    );
    // Nothing the image does not show is invented: every placed object is one of A's.
    assert!(
        got.objects.len() <= labelled.len(),
        "{} objects placed from {} labels",
        got.objects.len(),
        labelled.len()
    );
}

/// The ids of the labels whose instance value occurs in the guidance's `ids.png`: the objects
/// the image shows.
fn visible_labels(g: &Path) -> Vec<String> {
    let ids = image::open(g.join("ids.png")).unwrap().to_luma16();
    let values: std::collections::BTreeSet<u16> = ids.pixels().map(|p| p.0[0]).collect();
    let labels: Value =
        serde_json::from_slice(&std::fs::read(g.join("labels.json")).unwrap()).unwrap();
    labels
        .as_object()
        .unwrap()
        .iter()
        .filter(|(value, _)| values.contains(&value.parse::<u16>().unwrap()))
        .map(|(_, l)| l["id"].as_str().unwrap().to_owned())
        .collect()
}

/// The scene of `dir`'s `scene.json`.
fn scene_of(dir: &Path) -> Scene {
    Scene::read_json(&dir.join("scene.json")).unwrap()
}

/// `generate` with the guidance files and no prompt.
fn generate_photo_alone(g: &Path, out: &Path) -> Output {
    let out = out.to_str().unwrap();
    let args = [
        "generate",
        "--out",
        out,
        "--no-preview",
        "--max-replans",
        "0",
    ];
    with_guidance(&args, g)
}

/// A photo alone: no prompt, the scene the image shows — its labelled objects where it shows
/// them, and the report saying what was read from it. An image whose depth shows no floor
/// stops the run with one error naming the depth file, and nothing is written.
#[test]
fn a_photo_alone_builds_the_scene_it_shows() {
    let (scene, g) = base();
    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().join("photo");
    let out = generate_photo_alone(g, &out_dir);
    let t = text(&out);
    assert!(out.status.success(), "{t}");
    assert!(t.contains("inferred: no prompt"), "{t}");
    let report = report(&out_dir);
    let assumptions = report["assumptions"].to_string();
    assert!(assumptions.contains("no prompt"), "{report}");
    assert!(assumptions.contains("floor is visible"), "{report}");
    let truth = scene_of(scene);
    let labelled = visible_labels(g);
    let got = scene_of(&out_dir);
    let errors = recovery_errors(&truth, &labelled, &got);
    let within = errors.iter().filter(|e| **e < 0.10).count();
    assert!(
        within * 4 >= labelled.len() * 3,
        "{within} of {} labelled objects within 10 cm: {errors:?}",
        labelled.len()
    );
    assert!(
        got.objects.len() <= labelled.len(),
        "{} objects placed",
        got.objects.len()
    );

    // No floor in view: everything within a metre of the camera, nothing down at y = 0.
    let g = copy_guidance(dir.path());
    let near: Vec<f32> = (0..768 * 512)
        .map(|i| 0.8 + 0.0002 * (i % 768) as f32)
        .collect();
    std::fs::write(
        g.join("depth.npy"),
        scenethesis_vision::files::write_npy(768, 512, &near),
    )
    .unwrap();
    let out_dir = dir.path().join("no-floor");
    let out = generate_photo_alone(&g, &out_dir);
    let t = text(&out);
    assert!(!out.status.success(), "accepted without a floor\n{t}");
    assert!(
        t.contains("depth.npy") && t.contains("no visible floor"),
        "{t}"
    );
    assert!(!t.contains("✔ plan"), "the run started:\n{t}");
    assert!(!out_dir.exists(), "something was written");
}
