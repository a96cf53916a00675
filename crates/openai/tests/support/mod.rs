//! Test helpers: the crate's loopback test server (`scenethesis_openai::testing`) and a PNG maker.
#![allow(dead_code)]

pub use scenethesis_openai::testing::*;

/// A small real PNG.
pub fn png(width: u32, height: u32, rgb: [u8; 3]) -> Vec<u8> {
    let img = image::RgbImage::from_pixel(width, height, image::Rgb(rgb));
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}
