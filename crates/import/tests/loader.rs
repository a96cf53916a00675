//! The loader seam, proved by a loader of the test's own: a made-up `.box` format (three sizes
//! in file units) goes through the same folder import, normalisation, surface search and
//! resolver as the built-in GLB/glTF and OBJ loaders, and a loader added for a built-in
//! extension takes that extension over.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

use scenethesis_import::{
    AssetLoader, AssetResolver, Importer, ManifestEntry, MeshLoadError, MANIFEST_FILE,
};
use scenethesis_scene_graph::{AssetRef, Material, Mesh, MeshPart, Placement, SurfaceKind};

/// `.box` files: "width height depth", a box standing on y = 0 with its corner at the origin.
/// Counts its loads, so that a test can see which loader read a file.
#[derive(Default, Clone)]
struct BoxLoader {
    loads: Arc<AtomicUsize>,
    extensions: Vec<&'static str>,
}

impl BoxLoader {
    fn for_extensions(extensions: &[&'static str]) -> Self {
        Self {
            loads: Arc::default(),
            extensions: extensions.to_vec(),
        }
    }
}

impl AssetLoader for BoxLoader {
    fn extensions(&self) -> &[&str] {
        &self.extensions
    }

    fn load(&self, path: &Path, _root: &Path) -> Result<Mesh, MeshLoadError> {
        self.loads.fetch_add(1, Ordering::SeqCst);
        let text = std::fs::read_to_string(path)?;
        let sizes: Vec<f32> = text
            .split_whitespace()
            .map(|w| w.parse::<f32>())
            .collect::<Result<_, _>>()
            .map_err(|e| MeshLoadError::Unusable(format!("a size is not a number: {e}")))?;
        let [w, h, d] = sizes[..] else {
            return Err(MeshLoadError::Unusable(format!(
                "expected 3 sizes, found {}",
                sizes.len()
            )));
        };
        Ok(Mesh {
            parts: vec![MeshPart::cuboid("box", 0, [0.0; 3], [w, h, d])],
            materials: vec![Material {
                name: "cardboard".into(),
                base_color: [0.6, 0.45, 0.3, 1.0],
                roughness: 0.8,
                metallic: 0.0,
                texture: None,
            }],
        })
    }
}

fn write(dir: &Path, name: &str, text: &str) {
    std::fs::write(dir.join(name), text).unwrap();
}

#[test]
fn a_loader_of_ones_own_imports_a_folder_like_the_built_in_ones() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "crate.box", "40 30 60");
    write(dir.path(), "broken.box", "40 thirty");
    write(
        dir.path(),
        MANIFEST_FILE,
        r#"[
            { "file": "crate.box", "category": "storage_crate", "unit_scale": 0.01,
              "up_axis": "z", "front": "+x", "placement": "surface" },
            { "file": "broken.box", "category": "storage_crate" }
        ]"#,
    );
    let loader = BoxLoader::for_extensions(&["box"]);
    let importer = Importer::new().with_loader(loader.clone());
    let report = importer.import_directory(dir.path()).unwrap();
    assert_eq!(loader.loads.load(Ordering::SeqCst), 2);

    // The manifest's units, up axis and front apply to the new format's mesh: 40 x 30 x 60 cm,
    // z up (height 60 cm), front +x turned to +z (width and depth swap).
    assert_eq!(report.assets.len(), 1, "{:?}", report.warnings);
    let info = &report.assets[0].info;
    for (got, want) in info.size.iter().zip([0.3, 0.6, 0.4]) {
        assert!((got - want).abs() < 1e-5, "size {:?}", info.size);
    }
    assert_eq!(info.placement, Placement::Surface);
    assert!(
        info.support_surfaces
            .iter()
            .any(|s| s.kind == SurfaceKind::Top && (s.height - 0.6).abs() < 1e-4),
        "the top was found: {:?}",
        info.support_surfaces
    );
    assert!(matches!(&info.source, AssetRef::Imported { id, .. } if id == "crate"));

    // The loader's own error is the warning of the file it could not read.
    assert_eq!(report.warnings.len(), 1);
    let warning = report.warnings[0].to_string();
    assert!(
        warning.contains("broken.box") && warning.contains("not a number"),
        "{warning}"
    );

    // Without the loader the same folder imports nothing, and says why.
    let report = Importer::new().import_directory(dir.path()).unwrap();
    assert!(report.assets.is_empty());
    assert!(
        report.warnings[0]
            .to_string()
            .contains("unsupported file type (expected .glb, .gltf or .obj)"),
        "{}",
        report.warnings[0]
    );
}

#[test]
fn a_folder_without_manifest_lists_the_files_any_loader_reads() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "cube.box", "1 1 1");
    write(dir.path(), "notes.txt", "not a mesh");
    let importer = Importer::new().with_loader(BoxLoader::for_extensions(&["box"]));
    assert_eq!(importer.extensions(), ["box", "glb", "gltf", "obj"]);
    assert!(importer.loader_for(Path::new("CUBE.BOX")).is_some());
    assert!(importer.loader_for(Path::new("notes.txt")).is_none());
    let report = importer.import_directory(dir.path()).unwrap();
    let categories: Vec<&str> = report
        .assets
        .iter()
        .map(|a| a.info.category.as_str())
        .collect();
    assert_eq!(categories, ["cube"]);
    let err = importer
        .load_mesh(&dir.path().join("notes.txt"))
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "unsupported file type (expected .box, .glb, .gltf or .obj)"
    );
}

#[test]
fn a_loader_added_for_a_built_in_extension_reads_it_instead() {
    let dir = tempfile::tempdir().unwrap();
    // Not OBJ at all: only the replacement loader can read it.
    write(dir.path(), "shelf.obj", "2 1 0.5");
    let loader = BoxLoader::for_extensions(&["obj"]);
    let importer = Importer::new().with_loader(loader.clone());
    let entry: ManifestEntry =
        serde_json::from_str(r#"{ "file": "shelf.obj", "category": "shelf" }"#).unwrap();
    let asset = importer
        .import_entry(&dir.path().join("shelf.obj"), &entry)
        .unwrap();
    assert_eq!(asset.info.size, [2.0, 1.0, 0.5]);
    assert_eq!(loader.loads.load(Ordering::SeqCst), 1);
    assert!(scenethesis_import::import_entry(&dir.path().join("shelf.obj"), &entry).is_err());
}

#[test]
fn the_resolver_re_imports_with_the_loaders_it_was_given() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "crate.box", "0.4 0.3 0.6");
    let importer = Importer::new().with_loader(BoxLoader::for_extensions(&["box"]));
    let report = importer.import_directory(dir.path()).unwrap();
    let source = report.assets[0].info.source.clone();

    let mut resolver = AssetResolver::with_importer(
        Importer::new().with_loader(BoxLoader::for_extensions(&["box"])),
    );
    let asset = resolver.asset(&source).unwrap();
    assert_eq!(asset.info.size, report.assets[0].info.size);
    assert_eq!(asset.mesh, report.assets[0].mesh);

    // The default resolver has no loader for `.box`: the folder holds no such asset for it.
    let err = AssetResolver::new().asset(&source).unwrap_err();
    assert!(err.to_string().contains("no longer holds"), "{err}");
    // Procedural references resolve through the built-in library either way.
    let desk = AssetRef::Procedural {
        generator: "desk".into(),
        seed: 3,
        look: None,
    };
    assert_eq!(resolver.asset(&desk).unwrap().info.category, "desk");
}
