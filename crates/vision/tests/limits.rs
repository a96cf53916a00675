//! Guidance-file limits at their edge and just past it: image pixels (checked from the PNG
//! header and the `.npy` shape before decoding), label count, masks sized by the image.

use std::path::Path;

use scenethesis_vision::files::{
    check_image_size, parse_npy, read_depth, read_masks, read_rgb, MAX_LABELS, MAX_PIXELS,
};

/// CRC-32 (IEEE) of `bytes`, as PNG chunks need.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// One PNG chunk: length, type, data, CRC.
fn chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
    let mut body = kind.to_vec();
    body.extend_from_slice(data);
    let mut out = (data.len() as u32).to_be_bytes().to_vec();
    out.extend_from_slice(&body);
    out.extend_from_slice(&crc32(&body).to_be_bytes());
    out
}

/// A small PNG whose valid IHDR claims `width × height` 8-bit RGB pixels, followed by an
/// empty image-data chunk: the header reads, the pixels do not exist.
fn png_header(width: u32, height: u32) -> Vec<u8> {
    let mut ihdr = width.to_be_bytes().to_vec();
    ihdr.extend_from_slice(&height.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    out.extend(chunk(b"IHDR", &ihdr));
    out.extend(chunk(b"IDAT", &[]));
    out.extend(chunk(b"IEND", &[]));
    out
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

#[test]
fn the_pixel_budget_is_checked_at_its_edge_and_past_it() {
    assert!(check_image_size(4096, 4096).is_ok());
    assert_eq!(4096 * 4096, MAX_PIXELS);
    let e = check_image_size(4096, 4097).unwrap_err();
    assert!(e.contains("MAX_PIXELS") && e.contains("4096 × 4097"), "{e}");
    assert!(check_image_size(8192, 1).is_ok());
    assert!(check_image_size(8193, 1).unwrap_err().contains("1–8192"));
}

#[test]
fn a_png_header_claiming_a_huge_image_is_refused_before_decoding() {
    let dir = tempfile::tempdir().unwrap();
    for (w, h, expect) in [(100_000, 100_000, "1–8192"), (4097, 4096, "MAX_PIXELS")] {
        let path = write(dir.path(), "rgb.png", &png_header(w, h));
        let e = read_rgb(&path).unwrap_err().to_string();
        assert!(e.contains("rgb.png") && e.contains(expect), "{e}");
        let path = write(dir.path(), "depth.png", &png_header(w, h));
        let e = read_depth(&path).unwrap_err().to_string();
        assert!(e.contains("depth.png") && e.contains(expect), "{e}");
    }
    // At the limit the header passes and the missing pixel data is what is refused.
    let path = write(dir.path(), "rgb.png", &png_header(4096, 4096));
    let e = read_rgb(&path).unwrap_err().to_string();
    assert!(
        !e.contains("MAX_PIXELS") && e.contains("not a readable PNG"),
        "{e}"
    );
}

#[test]
fn an_npy_shape_over_the_pixel_budget_is_refused_before_its_data() {
    let npy = |h: u32, w: u32| {
        let mut header =
            format!("{{'descr': '<f4', 'fortran_order': False, 'shape': ({h}, {w}), }}");
        header.push('\n');
        let mut out = b"\x93NUMPY\x01\x00".to_vec();
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        out
    };
    let e = parse_npy(&npy(4097, 4096)).unwrap_err();
    assert!(e.contains("MAX_PIXELS"), "{e}");
    let e = parse_npy(&npy(4096, 4096)).unwrap_err();
    assert!(e.contains("data bytes"), "{e}");
}

fn ids_png(dir: &Path, w: u32, h: u32, value_at: impl Fn(u32, u32) -> u16) -> std::path::PathBuf {
    let img = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(w, h, |x, y| {
        image::Luma([value_at(x, y)])
    });
    let path = dir.join("ids.png");
    img.save(&path).unwrap();
    path
}

fn labels_json(dir: &Path, n: usize) -> std::path::PathBuf {
    let entries: Vec<String> = (1..=n)
        .map(|v| format!("\"{v}\": {{\"id\": \"thing_{v}\", \"category\": \"chair\"}}"))
        .collect();
    write(
        dir,
        "labels.json",
        format!("{{{}}}", entries.join(",")).as_bytes(),
    )
}

#[test]
fn only_labels_the_image_shows_get_a_mask_sized_by_its_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (300, 200);
    // Value 1 is a block, value 2 two far-apart pixels; the other 4094 labels are not shown.
    let ids = ids_png(dir.path(), w, h, |x, y| match (x, y) {
        (10..60, 20..50) => 1,
        (0, 0) | (299, 199) => 2,
        _ => 0,
    });
    let labels = labels_json(dir.path(), MAX_LABELS);
    let (masks, all) = read_masks(&ids, &labels).unwrap();
    assert_eq!(all.len(), MAX_LABELS);
    assert_eq!(masks.len(), 2);
    let block = &masks["thing_1"];
    assert_eq!(
        (block.area(), block.bounding_box()),
        (1500, Some((10, 20, 60, 50)))
    );
    let pair = &masks["thing_2"];
    assert_eq!(pair.pixels().collect::<Vec<_>>(), vec![(0, 0), (299, 199)]);
    let bytes: usize = masks.values().map(|m| m.heap_bytes()).sum();
    assert!(bytes <= 8 * (1500 + 2) + 64, "{bytes} bytes");
    // One label past the limit is refused, naming the file.
    let labels = labels_json(dir.path(), MAX_LABELS + 1);
    let e = read_masks(&ids, &labels).unwrap_err().to_string();
    assert!(e.contains("labels.json") && e.contains("MAX_LABELS"), "{e}");
}

#[test]
fn duplicate_keys_are_refused_naming_the_key() {
    let dir = tempfile::tempdir().unwrap();
    let ids = ids_png(dir.path(), 4, 4, |_, _| 1);
    let labels = write(
        dir.path(),
        "labels.json",
        br#"{"1": {"id": "sofa_0", "category": "sofa"}, "1": {"id": "sofa_1", "category": "sofa"}}"#,
    );
    let e = read_masks(&ids, &labels).unwrap_err().to_string();
    assert!(
        e.contains("labels.json") && e.contains("key `1` appears twice"),
        "{e}"
    );
}
