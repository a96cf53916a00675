//! Draws a generated floor plan as a top-view PNG for debugging:
//! `cargo run -p scenethesis-floorplan --example draw -- "a two-bedroom apartment" 3 out.png`.
//! Rooms are filled by type and labelled with their ids, walls are black, windows blue,
//! door leaves red (drawn open, from the hinge into the room they open into), passages green.

use image::{Rgb, RgbImage};
use nalgebra::{Point2, Vector2};
use scenethesis_floorplan::geometry::{rectangles, Rect};
use scenethesis_floorplan::{generate, DoorKind, Generated, Hinge, Knowledge, Program, Wall};

const SCALE: f64 = 60.0;
const MARGIN: f64 = 40.0;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [prompt, seed, out] = args.as_slice() else {
        return Err("usage: draw \"<prompt>\" <seed> <out.png>".into());
    };
    let k = Knowledge::builtin();
    let program = Program::from_words(k, prompt).ok_or("the prompt names no dwelling")?;
    let g = generate(k, &program, seed.parse()?)?;
    for note in &g.areas {
        println!(
            "{:<14} {:6.2} m² in [{}, {}]{}",
            note.room,
            note.area,
            note.range[0],
            note.range[1],
            if note.within {
                ""
            } else {
                "  (outside, within tolerance)"
            }
        );
    }
    for d in &g.plan.doors {
        println!(
            "{} {:?} {:?} w {:.2} swing {:?}",
            d.id,
            d.kind,
            d.rooms,
            d.width,
            d.swing.as_ref().map(|s| (&s.into, s.hinge))
        );
    }
    draw(&g).save(out)?;
    println!("wrote {out}");
    Ok(())
}

fn px(p: Point2<f64>) -> (f64, f64) {
    (MARGIN + p.x * SCALE, MARGIN + p.y * SCALE)
}

fn draw(g: &Generated) -> RgbImage {
    let [_, _, x1, z1] = g.footprint;
    let (w, h) = px(Point2::new(x1, z1));
    let mut img = RgbImage::from_pixel(
        (w + MARGIN) as u32,
        (h + MARGIN) as u32,
        Rgb([255, 255, 255]),
    );
    for room in &g.plan.rooms {
        let colour = colour_of(&room.room_type);
        let parts = rectangles(&room.polygon);
        for r in &parts {
            fill(&mut img, r, colour);
        }
        if let Some(big) = parts.iter().max_by(|a, b| a.area().total_cmp(&b.area())) {
            let c = px(nalgebra::center(&big.min, &big.max));
            label(&mut img, &room.id.to_uppercase(), c);
        }
    }
    for wall in &g.walls {
        line(&mut img, wall.start, wall.end, 3.0, Rgb([20, 20, 20]));
    }
    for window in &g.plan.windows {
        let wall = holder(&g.walls, &window.id);
        let d = direction(wall) * (window.width / 2.0);
        line(
            &mut img,
            window.centre - d,
            window.centre + d,
            4.0,
            Rgb([40, 110, 230]),
        );
    }
    for door in &g.plan.doors {
        let wall = holder(&g.walls, &door.id);
        let d = direction(wall);
        let (a, b) = (
            door.centre - d * (door.width / 2.0),
            door.centre + d * (door.width / 2.0),
        );
        let floor = g
            .plan
            .room(&door.rooms[0])
            .map_or(Rgb([255, 255, 255]), |r| colour_of(&r.room_type));
        line(&mut img, a, b, 4.0, floor);
        if door.kind == DoorKind::Passage {
            line(&mut img, a, b, 1.5, Rgb([30, 160, 60]));
            continue;
        }
        let Some(swing) = &door.swing else { continue };
        let n = if wall.rooms[0] == swing.into {
            wall.inward_normal()
        } else {
            -wall.inward_normal()
        };
        let view = -n;
        let right = Vector2::new(-view.y, view.x);
        let hinges: Vec<(Point2<f64>, f64)> = match swing.hinge {
            Hinge::Both => vec![(a, door.width / 2.0), (b, door.width / 2.0)],
            Hinge::Left | Hinge::Right => {
                let side = if swing.hinge == Hinge::Right {
                    1.0
                } else {
                    -1.0
                };
                let at = if (a - door.centre).dot(&right) * side > 0.0 {
                    a
                } else {
                    b
                };
                vec![(at, door.width)]
            }
        };
        for (at, len) in hinges {
            line(&mut img, at, at + n * len, 2.0, Rgb([210, 40, 40]));
        }
    }
    img
}

fn holder<'a>(walls: &'a [Wall], id: &str) -> &'a Wall {
    walls
        .iter()
        .find(|w| w.openings.iter().any(|o| o == id))
        .expect("every opening is on a wall")
}

fn direction(wall: &Wall) -> Vector2<f64> {
    (wall.end - wall.start).normalize()
}

fn colour_of(room_type: &str) -> Rgb<u8> {
    let h = room_type
        .bytes()
        .fold(7u32, |h, b| h.wrapping_mul(31).wrapping_add(u32::from(b)));
    let c = |s: u32| 170 + ((h >> s) % 80) as u8;
    Rgb([c(0), c(8), c(16)])
}

fn fill(img: &mut RgbImage, r: &Rect, colour: Rgb<u8>) {
    let (x0, y0) = px(r.min);
    let (x1, y1) = px(r.max);
    for y in y0 as u32..y1 as u32 {
        for x in x0 as u32..x1 as u32 {
            img.put_pixel(x, y, colour);
        }
    }
}

fn line(img: &mut RgbImage, a: Point2<f64>, b: Point2<f64>, width: f64, colour: Rgb<u8>) {
    let ((ax, ay), (bx, by)) = (px(a), px(b));
    let steps = ((bx - ax).abs().max((by - ay).abs()) * 2.0).max(1.0) as usize;
    let half = (width / 2.0) as i64;
    for s in 0..=steps {
        let t = s as f64 / steps as f64;
        let (x, y) = (ax + (bx - ax) * t, ay + (by - ay) * t);
        for dy in -half..=half {
            for dx in -half..=half {
                let (xx, yy) = (x as i64 + dx, y as i64 + dy);
                if xx >= 0 && yy >= 0 && (xx as u32) < img.width() && (yy as u32) < img.height() {
                    img.put_pixel(xx as u32, yy as u32, colour);
                }
            }
        }
    }
}

/// A 3x5 pixel font for labels, drawn at twice its size.
fn glyph(c: char) -> &'static str {
    match c {
        'A' => "010101111101101",
        'B' => "110101110101110",
        'C' => "011100100100011",
        'D' => "110101101101110",
        'E' => "111100110100111",
        'F' => "111100110100100",
        'G' => "011100101101011",
        'H' => "101101111101101",
        'I' => "111010010010111",
        'J' => "001001001101010",
        'K' => "101101110101101",
        'L' => "100100100100111",
        'M' => "101111111101101",
        'N' => "110101101101101",
        'O' => "010101101101010",
        'P' => "110101110100100",
        'Q' => "010101101110011",
        'R' => "110101110101101",
        'S' => "011100010001110",
        'T' => "111010010010010",
        'U' => "101101101101111",
        'V' => "101101101101010",
        'W' => "101101111111101",
        'X' => "101101010101101",
        'Y' => "101101010010010",
        'Z' => "111001010100111",
        '0' => "111101101101111",
        '1' => "010110010010111",
        '2' => "110001010100111",
        '3' => "110001010001110",
        '4' => "101101111001001",
        '5' => "111100110001110",
        '6' => "011100111101111",
        '7' => "111001010010010",
        '8' => "111101111101111",
        '9' => "111101111001110",
        '_' => "000000000000111",
        _ => "000000000000000",
    }
}

fn label(img: &mut RgbImage, text: &str, (cx, cy): (f64, f64)) {
    let advance = 8.0;
    let x0 = cx - advance * text.len() as f64 / 2.0;
    for (i, c) in text.chars().enumerate() {
        for (bit, on) in glyph(c).chars().enumerate() {
            if on != '1' {
                continue;
            }
            let (gx, gy) = ((bit % 3) as f64 * 2.0, (bit / 3) as f64 * 2.0);
            for (dx, dy) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)] {
                let (x, y) = (
                    (x0 + i as f64 * advance + gx + dx) as u32,
                    (cy - 5.0 + gy + dy) as u32,
                );
                if x < img.width() && y < img.height() {
                    img.put_pixel(x, y, Rgb([0, 0, 0]));
                }
            }
        }
    }
}
