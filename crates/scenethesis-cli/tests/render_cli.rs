//! `scenethesis render` on a real scene, rendering on the machine's adapter (llvmpipe in CI).

use std::process::Command;

#[test]
fn render_writes_photo_top_and_orbit_views_of_the_living_room() {
    let dir = tempfile::tempdir().unwrap();
    let fixture = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/scenes/valid_living_room.json"
    );
    std::fs::copy(fixture, dir.path().join("scene.json")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_scenethesis"))
        .args(["render", "--views", "2", "--size", "160x120", "--depth"])
        .arg(dir.path())
        .output()
        .expect("run scenethesis");
    let stderr = String::from_utf8_lossy(&out.stderr);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stderr}");
    // Every object of the fixture has a built-in generator: none may be skipped.
    assert!(!stderr.contains("skipping"), "{stderr}");
    assert!(stdout.contains("rendering 6 of 6 objects"), "{stdout}");
    for name in ["preview", "preview_top", "view_0", "view_1"] {
        let path = dir.path().join(format!("{name}.png"));
        let img = image::open(&path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .into_rgb8();
        assert_eq!(img.dimensions(), (160, 120), "{name}");
        let distinct: std::collections::BTreeSet<[u8; 3]> = img.pixels().map(|p| p.0).collect();
        assert!(distinct.len() > 50, "{name} looks blank");
        let npy = std::fs::read(dir.path().join(format!("{name}_depth.npy"))).unwrap();
        let (w, h, depth) = scenethesis_vision::files::parse_npy(&npy).unwrap();
        assert_eq!((w, h), (160, 120), "{name}_depth.npy");
        assert!(
            depth.iter().all(|d| d.is_finite() && *d >= 0.0) && depth.iter().any(|d| *d > 0.5),
            "{name}_depth.npy holds metres"
        );
    }
    assert!(!dir.path().join("view_2.png").exists());
}

#[test]
fn render_rejects_a_bad_size_clearly() {
    let out = Command::new(env!("CARGO_BIN_EXE_scenethesis"))
        .args([
            "render",
            "--size",
            "800",
            "fixtures/scenes/valid_living_room.json",
        ])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .expect("run scenethesis");
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("WIDTHxHEIGHT"), "{stderr}");
}
