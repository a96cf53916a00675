//! Exports `SCENETHESIS_MATERIALS_SOURCE_DIGEST`: a digest of this crate's version and of
//! every source file, which names the on-disk map cache (`kept.rs`), so that maps kept by a
//! build whose generator differed in any way are never read.

use std::fs;
use std::path::{Path, PathBuf};

fn main() {
    let root = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let mut files = Vec::new();
    collect(&root.join("src"), &mut files);
    files.sort();
    let mut digest = Fnv::default();
    digest.write(
        std::env::var("CARGO_PKG_VERSION")
            .unwrap_or_default()
            .as_bytes(),
    );
    for file in &files {
        let name = file.strip_prefix(&root).unwrap_or(file);
        digest.write(name.to_string_lossy().as_bytes());
        digest.write(&fs::read(file).expect("a source file of this crate is readable"));
    }
    println!("cargo:rerun-if-changed=src");
    println!(
        "cargo:rustc-env=SCENETHESIS_MATERIALS_SOURCE_DIGEST={:016x}",
        digest.0
    );
}

/// Every file under `dir`, recursively.
fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("the crate's src folder is readable") {
        let path = entry.expect("a readable folder entry").path();
        if path.is_dir() {
            collect(&path, out);
        } else {
            out.push(path);
        }
    }
}

/// 64-bit FNV-1a.
struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    fn write(&mut self, bytes: &[u8]) {
        // The length first, so that file boundaries count.
        for b in (bytes.len() as u64).to_le_bytes().iter().chain(bytes) {
            self.0 = (self.0 ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3);
        }
    }
}
