//! A binary per-pixel mask stored by what it covers, not by the image it lives in.
//!
//! A mask keeps either bits over a window of the image (dense objects) or the sorted list of
//! its pixels (scattered ones), whichever is smaller, so its memory is bounded by the pixels it
//! holds (at most 8 bytes each, plus a constant) and never by the image's size alone.

use serde::{Deserialize, Serialize};

use crate::error::GuidanceError;

/// A pixel window `(x0, y0, x1, y1)` with exclusive ends.
type Window = (u32, u32, u32, u32);

#[derive(Debug, Clone)]
enum Store {
    /// One bit per pixel of `window`, rows top to bottom.
    Bits { window: Window, bits: Vec<u64> },
    /// The pixels' row-major indices (`y · width + x`), sorted and distinct.
    List(Vec<u64>),
}

/// A binary per-pixel mask (one object's visible pixels), rows top to bottom.
///
/// Its memory grows with the pixels it holds (a bit window around them, or a pixel list when
/// they are scattered), not with the image: an empty mask of an 8192 × 8192 image costs a few
/// bytes.
///
/// In JSON (a segmenter's recorded answer) it is `{"width", "height", "pixels"}` with one
/// `true`/`false` per pixel, row-major.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(into = "MaskRecord", try_from = "MaskRecord")]
pub struct Mask {
    width: u32,
    height: u32,
    store: Store,
}

/// A [`Mask`] as written to JSON.
#[derive(Serialize, Deserialize)]
struct MaskRecord {
    width: u32,
    height: u32,
    pixels: Vec<bool>,
}

impl From<Mask> for MaskRecord {
    fn from(m: Mask) -> Self {
        Self {
            width: m.width,
            height: m.height,
            pixels: m.to_flags(),
        }
    }
}

impl TryFrom<MaskRecord> for Mask {
    type Error = GuidanceError;

    fn try_from(r: MaskRecord) -> Result<Self, GuidanceError> {
        Mask::from_flags(r.width, r.height, r.pixels)
    }
}

fn window_area(w: &Window) -> u64 {
    (w.2 - w.0) as u64 * (w.3 - w.1) as u64
}

fn words(w: &Window) -> usize {
    window_area(w).div_ceil(64) as usize
}

impl Mask {
    /// An empty `width × height` mask.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            store: Store::Bits {
                window: (0, 0, 0, 0),
                bits: Vec::new(),
            },
        }
    }

    /// An empty mask that will hold about `area` pixels inside `bbox` (`(x0, y0, x1, y1)`,
    /// exclusive ends, clipped to the image), stored in the cheaper of a bit window and a
    /// pixel list. Pixels set later outside `bbox` are still kept.
    pub fn with_bounds(width: u32, height: u32, bbox: Window, area: usize) -> Self {
        let window = (
            bbox.0.min(width),
            bbox.1.min(height),
            bbox.2.min(width).max(bbox.0.min(width)),
            bbox.3.min(height).max(bbox.1.min(height)),
        );
        let bits_bytes = words(&window) as u64 * 8;
        let list_bytes = area as u64 * 8;
        let store = if bits_bytes <= list_bytes.saturating_add(64) {
            Store::Bits {
                window,
                bits: vec![0; words(&window)],
            }
        } else {
            Store::List(Vec::with_capacity(area))
        };
        Self {
            width,
            height,
            store,
        }
    }

    /// A mask from `width × height` flags, row-major.
    pub fn from_flags(width: u32, height: u32, data: Vec<bool>) -> Result<Self, GuidanceError> {
        let expected = width as usize * height as usize;
        if data.len() != expected {
            return Err(GuidanceError::BufferSize {
                what: "mask".to_owned(),
                width,
                height,
                len: data.len(),
                expected,
            });
        }
        let mut mask = Self::new(width, height);
        for (i, _) in data.iter().enumerate().filter(|(_, &m)| m) {
            mask.set(
                (i % width as usize) as u32,
                (i / width as usize) as u32,
                true,
            );
        }
        Ok(mask)
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    fn index(&self, x: u32, y: u32) -> u64 {
        y as u64 * self.width as u64 + x as u64
    }

    /// Whether pixel (x, y) belongs to the mask (`false` outside the image).
    pub fn contains(&self, x: u32, y: u32) -> bool {
        if x >= self.width || y >= self.height {
            return false;
        }
        match &self.store {
            Store::Bits { window, bits } => bit_at(window, bits, x, y).is_some_and(|b| {
                let (word, mask) = b;
                bits[word] & mask != 0
            }),
            Store::List(list) => list.binary_search(&self.index(x, y)).is_ok(),
        }
    }

    /// Sets pixel (x, y); ignored outside the image.
    pub fn set(&mut self, x: u32, y: u32, value: bool) {
        if x >= self.width || y >= self.height {
            return;
        }
        let index = self.index(x, y);
        let (width, height) = (self.width, self.height);
        match &mut self.store {
            Store::Bits { window, bits } => {
                if bit_at(window, bits, x, y).is_none() {
                    if !value {
                        return;
                    }
                    grow(window, bits, (x, y), (width, height));
                }
                let (word, mask) = bit_at(window, bits, x, y).expect("the window holds (x, y)");
                if value {
                    bits[word] |= mask;
                } else {
                    bits[word] &= !mask;
                }
            }
            Store::List(list) => set_in_list(list, index, value),
        }
    }

    /// The pixels' row-major flags, `width × height` of them.
    pub fn to_flags(&self) -> Vec<bool> {
        let mut flags = vec![false; self.width as usize * self.height as usize];
        for (x, y) in self.pixels() {
            flags[self.index(x, y) as usize] = true;
        }
        flags
    }

    /// Number of pixels in the mask.
    pub fn area(&self) -> usize {
        match &self.store {
            Store::Bits { bits, .. } => bits.iter().map(|w| w.count_ones() as usize).sum(),
            Store::List(list) => list.len(),
        }
    }

    /// The pixels in the mask as (x, y), row by row.
    pub fn pixels(&self) -> Box<dyn Iterator<Item = (u32, u32)> + '_> {
        match &self.store {
            Store::Bits { window, bits } => {
                let ww = (window.2 - window.0) as u64;
                let (x0, y0) = (window.0, window.1);
                Box::new(
                    set_bits(bits)
                        .map(move |i| (x0 + (i % ww.max(1)) as u32, y0 + (i / ww.max(1)) as u32)),
                )
            }
            Store::List(list) => {
                let w = self.width as u64;
                Box::new(list.iter().map(move |i| ((i % w) as u32, (i / w) as u32)))
            }
        }
    }

    /// The tight pixel box `(x0, y0, x1, y1)` (exclusive ends) or `None` when empty.
    pub fn bounding_box(&self) -> Option<(u32, u32, u32, u32)> {
        let mut b: Option<Window> = None;
        for (x, y) in self.pixels() {
            b = Some(match b {
                None => (x, y, x + 1, y + 1),
                Some((x0, y0, x1, y1)) => (x0.min(x), y0.min(y), x1.max(x + 1), y1.max(y + 1)),
            });
        }
        b
    }

    /// Bytes the mask's pixels take on the heap (its storage, not counting spare capacity).
    pub fn heap_bytes(&self) -> usize {
        match &self.store {
            Store::Bits { bits, .. } => bits.len() * 8,
            Store::List(list) => list.len() * 8,
        }
    }
}

impl PartialEq for Mask {
    fn eq(&self, other: &Self) -> bool {
        (self.width, self.height) == (other.width, other.height) && self.pixels().eq(other.pixels())
    }
}

impl Eq for Mask {}

/// The word and bit of (x, y) in a bit window, `None` outside it.
fn bit_at(window: &Window, bits: &[u64], x: u32, y: u32) -> Option<(usize, u64)> {
    let inside = x >= window.0 && x < window.2 && y >= window.1 && y < window.3;
    if !inside || bits.is_empty() {
        return None;
    }
    let i = (y - window.1) as u64 * (window.2 - window.0) as u64 + (x - window.0) as u64;
    Some(((i / 64) as usize, 1 << (i % 64)))
}

/// The indices of the set bits, in order.
fn set_bits(bits: &[u64]) -> impl Iterator<Item = u64> + '_ {
    bits.iter().enumerate().flat_map(|(w, &word)| {
        let mut rest = word;
        std::iter::from_fn(move || {
            (rest != 0).then(|| {
                let b = rest.trailing_zeros() as u64;
                rest &= rest - 1;
                w as u64 * 64 + b
            })
        })
    })
}

/// Grows a bit window to hold `(x, y)`: at least doubled in each direction it grows (clipped
/// to the image), so pixels set in row order cost amortised constant time.
fn grow(window: &mut Window, bits: &mut Vec<u64>, (x, y): (u32, u32), (w, h): (u32, u32)) {
    let old = *window;
    let empty = bits.is_empty();
    let (ow, oh) = (old.2 - old.0, old.3 - old.1);
    let mut new = if empty {
        (x, y, x + 1, y + 1)
    } else {
        (
            old.0.min(x),
            old.1.min(y),
            old.2.max(x + 1),
            old.3.max(y + 1),
        )
    };
    if !empty {
        if new.0 < old.0 {
            new.0 = new.0.min(old.0.saturating_sub(ow));
        }
        if new.2 > old.2 {
            new.2 = new.2.max(old.2.saturating_add(ow)).min(w);
        }
        if new.1 < old.1 {
            new.1 = new.1.min(old.1.saturating_sub(oh));
        }
        if new.3 > old.3 {
            new.3 = new.3.max(old.3.saturating_add(oh)).min(h);
        }
    }
    let mut grown = vec![0u64; words(&new)];
    if !empty {
        let nw = (new.2 - new.0) as u64;
        for i in set_bits(bits) {
            let (px, py) = (old.0 as u64 + i % ow as u64, old.1 as u64 + i / ow as u64);
            let j = (py - new.1 as u64) * nw + (px - new.0 as u64);
            grown[(j / 64) as usize] |= 1 << (j % 64);
        }
    }
    *window = new;
    *bits = grown;
}

/// Adds or removes `index` in a sorted pixel list (appending in row order is constant time).
fn set_in_list(list: &mut Vec<u64>, index: u64, value: bool) {
    if value && list.last().is_none_or(|&last| last < index) {
        list.push(index);
        return;
    }
    match (list.binary_search(&index), value) {
        (Err(at), true) => list.insert(at, index),
        (Ok(at), false) => {
            list.remove(at);
        }
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixels(m: &Mask) -> Vec<(u32, u32)> {
        m.pixels().collect()
    }

    #[test]
    fn a_mask_built_in_any_order_holds_its_pixels_in_row_order() {
        let mut m = Mask::new(50, 40);
        for &(x, y) in &[(30, 20), (5, 3), (49, 39), (0, 0), (31, 20)] {
            m.set(x, y, true);
        }
        assert_eq!(
            pixels(&m),
            vec![(0, 0), (5, 3), (30, 20), (31, 20), (49, 39)]
        );
        assert_eq!(m.area(), 5);
        assert_eq!(m.bounding_box(), Some((0, 0, 50, 40)));
        m.set(49, 39, false);
        m.set(10, 10, false);
        assert!(!m.contains(49, 39) && m.contains(31, 20) && !m.contains(50, 0));
        assert_eq!(m.bounding_box(), Some((0, 0, 32, 21)));
    }

    #[test]
    fn the_cheaper_store_is_chosen_and_both_agree() {
        // Two far corners: a bit window would cover the whole image, the list holds 2.
        let mut far = Mask::with_bounds(4096, 4096, (0, 0, 4096, 4096), 2);
        far.set(0, 0, true);
        far.set(4095, 4095, true);
        assert_eq!(far.heap_bytes(), 16);
        // A filled rectangle: bits, far below 8 bytes per pixel.
        let mut block = Mask::with_bounds(4096, 4096, (10, 10, 110, 60), 5000);
        for y in 10..60 {
            for x in 10..110 {
                block.set(x, y, true);
            }
        }
        assert!(block.heap_bytes() <= 5000 / 8 + 8, "{}", block.heap_bytes());
        let mut same = Mask::new(4096, 4096);
        for (x, y) in block.pixels() {
            same.set(x, y, true);
        }
        assert_eq!(block, same);
        assert_ne!(far, same);
        assert_eq!(far.to_flags().iter().filter(|&&f| f).count(), 2);
    }

    #[test]
    fn a_mask_round_trips_through_json_as_flags() {
        let mut m = Mask::new(3, 2);
        m.set(2, 1, true);
        let json = serde_json::to_string(&m).unwrap();
        assert_eq!(
            json,
            r#"{"width":3,"height":2,"pixels":[false,false,false,false,false,true]}"#
        );
        assert_eq!(serde_json::from_str::<Mask>(&json).unwrap(), m);
        assert!(serde_json::from_str::<Mask>(r#"{"width":3,"height":2,"pixels":[true]}"#).is_err());
    }

    #[test]
    fn an_empty_mask_of_a_large_image_costs_nothing() {
        let m = Mask::new(8192, 8192);
        assert_eq!((m.heap_bytes(), m.area(), m.bounding_box()), (0, 0, None));
        assert!(!m.contains(100, 100));
    }

    #[test]
    fn a_mask_grown_row_by_row_stays_near_its_box() {
        let mut m = Mask::new(8192, 8192);
        for y in 100..300 {
            for x in 200..400 {
                m.set(x, y, true);
            }
        }
        assert_eq!(m.area(), 40_000);
        // At most 4× the box's bits.
        assert!(m.heap_bytes() <= 4 * 40_000 / 8 + 64, "{}", m.heap_bytes());
        assert_eq!(m.bounding_box(), Some((200, 100, 400, 300)));
    }
}
