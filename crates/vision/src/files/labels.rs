//! `labels.json` and `ids.png`: the labels of an instance image and the masks they stand for.
//!
//! Labels are checked while they are parsed (count, duplicate keys), masks are made only for
//! the labels the image shows and stored by their pixels, so memory is bounded by the image's
//! size, not by labels × image.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::Path;

use image::{ImageBuffer, Luma};
use scenethesis_imagery::Mask;
use scenethesis_scene_graph::{is_printable_id, limits::MAX_ID_BYTES, printable};
use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};

use super::{decode_png, invalid, read_bounded_to, FileError, Label, Labels};

/// Most labels a `labels.json` may hold.
pub const MAX_LABELS: usize = 4096;
/// Largest `labels.json` read, in bytes (16 MiB).
pub const MAX_LABELS_JSON_BYTES: u64 = 16 << 20;

/// The entries of a `labels.json` in file order, refusing a repeated key and more than
/// [`MAX_LABELS`] entries while parsing.
struct RawLabels(Vec<(String, Label)>);

impl<'de> Deserialize<'de> for RawLabels {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_map(RawLabelsVisitor)
    }
}

struct RawLabelsVisitor;

impl<'de> Visitor<'de> for RawLabelsVisitor {
    type Value = RawLabels;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an object {\"VALUE\": {\"id\": …, \"category\": …}, …}")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<RawLabels, A::Error> {
        let mut seen = BTreeSet::new();
        let mut entries = Vec::new();
        while let Some(key) = map.next_key::<String>()? {
            if entries.len() == MAX_LABELS {
                return Err(de::Error::custom(format!(
                    "more than {MAX_LABELS} labels (the limit MAX_LABELS)"
                )));
            }
            if !seen.insert(key.clone()) {
                return Err(de::Error::custom(format!(
                    "key `{}` appears twice; each instance value must be labelled once",
                    printable(&key)
                )));
            }
            entries.push((key, map.next_value::<Label>()?));
        }
        Ok(RawLabels(entries))
    }
}

/// Parses `labels.json` bytes: at most [`MAX_LABELS`] distinct keys `1`–`65535`, each with a
/// printable id and category of at most `MAX_ID_BYTES` bytes, ids distinct.
pub fn parse_labels(path: &Path, bytes: &[u8]) -> Result<Labels, FileError> {
    let raw: RawLabels = serde_json::from_slice(bytes).map_err(|e| {
        invalid(
            path,
            format!("expected {{\"VALUE\": {{\"id\": …, \"category\": …}}, …}} ({e})"),
        )
    })?;
    let mut labels = BTreeMap::new();
    let mut ids = BTreeMap::new();
    for (key, label) in raw.0 {
        let value = instance_value(path, &key)?;
        check_label_text(path, value, "id", &label.id)?;
        check_label_text(path, value, "category", &label.category)?;
        if let Some(other) = ids.insert(label.id.clone(), value) {
            return Err(invalid(
                path,
                format!("labels {other} and {value} both name object `{}`", label.id),
            ));
        }
        labels.insert(value, label);
    }
    Ok(labels)
}

fn instance_value(path: &Path, key: &str) -> Result<u16, FileError> {
    key.parse().ok().filter(|v| *v != 0).ok_or_else(|| {
        invalid(
            path,
            format!("key `{}` is not an instance value 1–65535", printable(key)),
        )
    })
}

fn check_label_text(path: &Path, value: u16, field: &str, text: &str) -> Result<(), FileError> {
    if is_printable_id(text) {
        return Ok(());
    }
    let shown = if text.len() > 64 {
        format!("{} bytes long", text.len())
    } else {
        format!("`{}`", printable(text))
    };
    Err(invalid(
        path,
        format!(
            "label {value}: {field} {shown}: expected 1 to {MAX_ID_BYTES} bytes of printable \
             characters (no control or bidirectional formatting characters, no leading or \
             trailing spaces)"
        ),
    ))
}

/// Reads `ids.png` as 16-bit instance values (8-bit images are widened).
fn read_instances(ids_png: &Path) -> Result<ImageBuffer<Luma<u16>, Vec<u16>>, FileError> {
    match decode_png(ids_png)? {
        image::DynamicImage::ImageLuma16(i) => Ok(i),
        image::DynamicImage::ImageLuma8(i) => {
            let (w, h) = i.dimensions();
            Ok(
                ImageBuffer::from_raw(w, h, i.into_raw().into_iter().map(u16::from).collect())
                    .expect("one value per pixel"),
            )
        }
        other => Err(invalid(
            ids_png,
            format!(
                "an instance image must be 8- or 16-bit greyscale, found {:?}",
                other.color()
            ),
        )),
    }
}

/// Pixel count and bounding box `(x0, y0, x1, y1)` of one instance value.
#[derive(Clone, Copy)]
struct Extent {
    area: usize,
    bbox: (u32, u32, u32, u32),
}

/// The extent of every instance value in the image, checking each non-zero value is labelled.
fn extents(
    img: &ImageBuffer<Luma<u16>, Vec<u16>>,
    labels: &Labels,
    ids_png: &Path,
    labels_json: &Path,
) -> Result<BTreeMap<u16, Extent>, FileError> {
    let mut table: Vec<Option<Extent>> = vec![None; 1 << 16];
    for (x, y, px) in img.enumerate_pixels() {
        let v = px.0[0];
        if v == 0 {
            continue;
        }
        let slot = &mut table[v as usize];
        match slot {
            Some(e) => {
                e.area += 1;
                e.bbox = (
                    e.bbox.0.min(x),
                    e.bbox.1.min(y),
                    e.bbox.2.max(x + 1),
                    e.bbox.3.max(y + 1),
                );
            }
            None if labels.contains_key(&v) => {
                *slot = Some(Extent {
                    area: 1,
                    bbox: (x, y, x + 1, y + 1),
                })
            }
            None => {
                return Err(invalid(
                    ids_png,
                    format!(
                        "pixel ({x}, {y}) has instance value {v}, which {} does not label",
                        labels_json.display()
                    ),
                ))
            }
        }
    }
    Ok(table
        .into_iter()
        .enumerate()
        .filter_map(|(v, e)| Some((v as u16, e?)))
        .collect())
}

/// Reads `ids.png` + `labels.json` into one mask per object id the image shows (a label whose
/// value does not occur in the image gets none) and all labels. Every non-zero value in the
/// image must have a label; labels must have distinct printable ids. Each mask is stored by its
/// pixels, so the masks together take at most about 8 bytes per image pixel.
pub fn read_masks(
    ids_png: &Path,
    labels_json: &Path,
) -> Result<(BTreeMap<String, Mask>, Labels), FileError> {
    let bytes = read_bounded_to(labels_json, MAX_LABELS_JSON_BYTES)?;
    let labels = parse_labels(labels_json, &bytes)?;
    let img = read_instances(ids_png)?;
    let (w, h) = img.dimensions();
    let extents = extents(&img, &labels, ids_png, labels_json)?;
    let mut by_value: BTreeMap<u16, Mask> = extents
        .iter()
        .map(|(v, e)| (*v, Mask::with_bounds(w, h, e.bbox, e.area)))
        .collect();
    for (x, y, px) in img.enumerate_pixels() {
        if let Some(mask) = by_value.get_mut(&px.0[0]) {
            mask.set(x, y, true);
        }
    }
    let masks = by_value
        .into_iter()
        .map(|(v, m)| (labels[&v].id.clone(), m))
        .collect();
    Ok((masks, labels))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Labels, String> {
        parse_labels(Path::new("labels.json"), text.as_bytes()).map_err(|e| e.to_string())
    }

    fn entry(value: usize, id: &str) -> String {
        format!("\"{value}\": {{\"id\": \"{id}\", \"category\": \"chair\"}}")
    }

    fn many(n: usize) -> String {
        let entries: Vec<String> = (1..=n).map(|v| entry(v, &format!("chair_{v}"))).collect();
        format!("{{{}}}", entries.join(","))
    }

    #[test]
    fn the_label_count_is_capped_at_max_labels() {
        assert_eq!(parse(&many(MAX_LABELS)).unwrap().len(), MAX_LABELS);
        let e = parse(&many(MAX_LABELS + 1)).unwrap_err();
        assert!(
            e.contains("labels.json") && e.contains("more than 4096 labels"),
            "{e}"
        );
    }

    #[test]
    fn a_repeated_key_is_refused_naming_it() {
        let text = format!("{{{}, {}}}", entry(3, "a"), entry(3, "b"));
        let e = parse(&text).unwrap_err();
        assert!(e.contains("key `3` appears twice"), "{e}");
        let text = format!("{{{}, {}}}", entry(3, "a"), entry(4, "b"));
        assert_eq!(parse(&text).unwrap().len(), 2);
    }

    #[test]
    fn ids_follow_the_scene_validators_printable_rule() {
        let at_limit = "a".repeat(MAX_ID_BYTES);
        let text = format!("{{{}}}", entry(1, &at_limit));
        assert_eq!(parse(&text).unwrap()[&1].id, at_limit);
        let past = "a".repeat(MAX_ID_BYTES + 1);
        let e = parse(&format!("{{{}}}", entry(1, &past))).unwrap_err();
        assert!(
            e.contains("label 1: id 257 bytes long") && e.contains("1 to 256 bytes"),
            "{e}"
        );
        let e = parse(&format!("{{{}}}", entry(2, "evil\u{202e}txt"))).unwrap_err();
        assert!(e.contains("label 2: id") && e.contains("\\u{202e}"), "{e}");
        let e = parse(&format!("{{{}}}", entry(2, "tab\\u0009"))).unwrap_err();
        assert!(e.contains("label 2: id"), "{e}");
        let e = parse(r#"{"5": {"id": "ok", "category": " chair"}}"#).unwrap_err();
        assert!(e.contains("label 5: category"), "{e}");
    }
}
