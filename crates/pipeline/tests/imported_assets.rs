//! Bring-your-own assets through the whole pipeline: a folder with an OBJ (+ MTL) and an
//! `assets.json` manifest is imported, retrieved in preference to the built-in generator of its
//! category, placed, judged, written and re-exported from the saved folder.

use std::fmt::Write as _;
use std::path::Path;

use scenethesis_pipeline::{
    export_folder, AssetError, AssetSource, Format, GenerateOptions, NoProgress, Pipeline,
    PipelineError, RetrievalSource,
};
use scenethesis_procedural::catalog;
use scenethesis_scene_graph::{AssetRef, Mesh, Scene};

/// Writes `mesh` as an OBJ in centimetres with Z up (so the import has to convert both), one
/// group per part, with its materials in an MTL file next to it.
fn write_obj(mesh: &Mesh, dir: &Path, stem: &str) {
    let mut mtl = String::new();
    for m in &mesh.materials {
        let [r, g, b, _] = m.base_color;
        writeln!(mtl, "newmtl {}\nKd {r} {g} {b}\n", m.name).unwrap();
    }
    std::fs::write(dir.join(format!("{stem}.mtl")), mtl).unwrap();
    let mut obj = format!("mtllib {stem}.mtl\n");
    let mut base = 1;
    for part in &mesh.parts {
        writeln!(obj, "g {}", part.name).unwrap();
        writeln!(obj, "usemtl {}", mesh.materials[part.material].name).unwrap();
        for [x, y, z] in &part.positions {
            // +Y up → +Z up: (x, y, z) ↦ (x, −z, y); metres → centimetres.
            writeln!(obj, "v {} {} {}", x * 100.0, -z * 100.0, y * 100.0).unwrap();
        }
        for t in &part.triangles {
            writeln!(obj, "f {} {} {}", base + t[0], base + t[1], base + t[2]).unwrap();
        }
        base += part.positions.len() as u32;
    }
    std::fs::write(dir.join(format!("{stem}.obj")), obj).unwrap();
}

/// A bring-your-own folder holding one armchair (a reshaped built-in one, so it is a real
/// closed multi-part mesh) described by a manifest with a non-default unit and up axis.
fn asset_folder(dir: &Path) -> Mesh {
    std::fs::create_dir_all(dir).unwrap();
    let mut mesh = catalog::generate(catalog::category("armchair").unwrap(), 11).mesh;
    // Make it recognisably ours: wider and in our own colour.
    for part in &mut mesh.parts {
        for p in &mut part.positions {
            p[0] *= 1.15;
        }
    }
    for m in &mut mesh.materials {
        m.name = format!("grandma_{}", m.name);
        m.base_color = [0.55, 0.12, 0.2, 1.0];
    }
    write_obj(&mesh, dir, "wingback");
    std::fs::write(
        dir.join("assets.json"),
        r#"[{ "file": "wingback.obj", "id": "grandmas_chair", "category": "armchair",
              "synonyms": ["wingback chair"], "up_axis": "z", "unit_scale": 0.01 }]"#,
    )
    .unwrap();
    mesh
}

const PROMPT: &str = "a cozy living room with an armchair next to a floor lamp";

#[test]
fn imported_assets_are_retrieved_placed_written_and_reexported() {
    let tmp = tempfile::tempdir().unwrap();
    let assets_dir = tmp.path().join("my_assets");
    let original = asset_folder(&assets_dir);

    let (source, warnings) = RetrievalSource::from_directory(&assets_dir).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(source.imported_count(), 1);
    let pipeline = Pipeline::offline().with_assets(source);
    let options = GenerateOptions {
        max_replans: 2,
        previews: false,
        ..GenerateOptions::default()
    };
    let mut generated = pipeline
        .generate(PROMPT, 3, &options, &mut NoProgress)
        .expect("generation with imported assets works");
    let chairs: Vec<_> = generated
        .scene
        .objects
        .iter()
        .filter(|o| o.category == "armchair")
        .collect();
    assert!(
        !chairs.is_empty(),
        "the prompt asks for an armchair: {:?}\n{}",
        generated
            .scene
            .objects
            .iter()
            .map(|o| (&o.id, &o.asset))
            .collect::<Vec<_>>(),
        serde_json::to_string_pretty(&generated.report).unwrap()
    );
    for chair in &chairs {
        assert!(
            matches!(&chair.asset, AssetRef::Imported { id, .. } if id == "grandmas_chair"),
            "{} uses {} instead of the imported armchair",
            chair.id,
            chair.asset
        );
        // The mesh placed is the imported one, converted back to metres and +Y up.
        let mesh = &generated.meshes[&chair.id];
        assert_eq!(mesh.triangle_count(), original.triangle_count());
        assert!(mesh
            .materials
            .iter()
            .all(|m| m.name.starts_with("grandma_")));
        let (a, b) = (mesh.bounds().unwrap(), original.bounds().unwrap());
        for k in 0..3 {
            let (ea, eb) = (a.max[k] - a.min[k], b.max[k] - b.min[k]);
            assert!((ea - eb).abs() < 1e-4, "extent {k}: {ea} vs {eb}");
        }
    }
    // Other categories still come from the built-in library.
    assert!(generated
        .scene
        .objects
        .iter()
        .any(|o| matches!(o.asset, AssetRef::Procedural { .. })));
    assert!(
        generated.report.accepted,
        "{:?}",
        generated.report.verdict.failures
    );

    let out = tmp.path().join("scene");
    generated.write_outputs(&out).unwrap();
    let saved = Scene::read_json(&out.join("scene.json")).unwrap();
    assert!(saved
        .objects
        .iter()
        .any(|o| matches!(&o.asset, AssetRef::Imported { id, .. } if id == "grandmas_chair")));
    let glb = gltf::Gltf::open(out.join("scene.glb")).unwrap();
    let names: Vec<&str> = glb.materials().filter_map(|m| m.name()).collect();
    assert!(
        names.iter().any(|n| n.starts_with("grandma_")),
        "imported materials kept in the GLB: {names:?}"
    );

    // A saved scene re-exports from the paths in scene.json, with no source in memory.
    let written = export_folder(
        &out,
        &[Format::Mjcf, Format::Usd],
        &RetrievalSource::default(),
    )
    .expect("re-export re-imports the asset folder");
    assert_eq!(written.len(), 2);

    // Once the folder is gone, the error names the asset and the directory.
    std::fs::remove_dir_all(&assets_dir).unwrap();
    let err = export_folder(&out, &[Format::Urdf], &RetrievalSource::default()).unwrap_err();
    let text = err.to_string();
    assert!(
        matches!(err, PipelineError::Asset(AssetError::Unresolvable { .. })),
        "{text}"
    );
    assert!(
        text.contains("grandmas_chair") && text.contains("my_assets"),
        "{text}"
    );
}

#[test]
fn an_asset_folder_without_meshes_is_a_clear_error() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("notes.txt"), "not a mesh").unwrap();
    let err = RetrievalSource::from_directory(tmp.path()).unwrap_err();
    assert!(matches!(err, AssetError::Import { .. }), "{err}");
    assert!(
        err.to_string().contains("no asset could be imported"),
        "{err}"
    );
    // The built-in library still answers for every category it has.
    let source = RetrievalSource::default();
    assert!(source.categories().contains("armchair"));
}
