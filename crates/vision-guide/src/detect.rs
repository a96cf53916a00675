//! Masks for the planned objects: matching given labels to the plan, or asking a
//! vision-language model for one box per visible planned object and turning the boxes into
//! masks (with a box-prompted segmenter, or the boxes themselves).

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_agents::Plan;
use scenethesis_imagery::Mask;
use scenethesis_models::{
    BoxPrompt, ChatModel, ChatRequest, ImageData, JsonSchema, Message, Segmenter,
};
use scenethesis_vision::files::Labels;
use serde_json::{json, Value};

/// A planned object's box in normalised image coordinates `[x0, y0, x1, y1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectBox {
    /// The planned object's id.
    pub id: String,
    /// The box, in [0, 1], origin top left, `x0 < x1`, `y0 < y1`.
    pub bbox: [f32; 4],
}

/// How the labels of an instance image meet the plan ([`assign_labels`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LabelMatch {
    /// Planned object id by label id.
    pub assigned: BTreeMap<String, String>,
    /// Labels the instance image does not show, with why.
    pub invisible: Vec<(String, String)>,
    /// Visible labels no planned object is left for: `(label id, category)`, in label order.
    pub unplanned: Vec<(String, String)>,
}

/// Assigns labels to planned objects: a label whose id is planned with the label's category
/// keeps it; otherwise the first planned object of the label's category not yet taken gets it.
/// Labels whose value does not occur in the instance image (no mask) guide nothing.
pub fn assign_labels(plan: &Plan, masks: &BTreeMap<String, Mask>, labels: &Labels) -> LabelMatch {
    let mut out = LabelMatch::default();
    let mut taken: BTreeSet<String> = BTreeSet::new();
    let mut handled: BTreeSet<&str> = BTreeSet::new();
    for (value, label) in labels {
        if !masks.contains_key(&label.id) {
            handled.insert(label.id.as_str());
            out.invisible.push((
                label.id.clone(),
                format!("labelled but not visible: instance value {value} does not occur in the instance image"),
            ));
        }
    }
    // Ids first, so a category match never steals an object a label names.
    for label in labels.values() {
        if handled.contains(label.id.as_str()) {
            continue;
        }
        if let Some(o) = plan.object(&label.id) {
            if o.category == label.category && taken.insert(o.id.clone()) {
                out.assigned.insert(label.id.clone(), o.id.clone());
                handled.insert(label.id.as_str());
            }
        }
    }
    for label in labels.values() {
        if handled.contains(label.id.as_str()) {
            continue;
        }
        let free = plan
            .objects
            .iter()
            .find(|o| o.category == label.category && !taken.contains(&o.id));
        match free {
            Some(o) => {
                taken.insert(o.id.clone());
                out.assigned.insert(label.id.clone(), o.id.clone());
            }
            None => out
                .unplanned
                .push((label.id.clone(), label.category.clone())),
        }
    }
    out
}

/// The labelled masks by planned id ([`assign_labels`]) and, for labels no planned object
/// matches or that have no mask, `(label id, why)`. The vision guide adopts every labelled
/// object into the plan before the layout, so a label is left without an object only when a
/// re-plan dropped its object or the plan was full.
pub fn match_labels(
    plan: &Plan,
    masks: &BTreeMap<String, Mask>,
    labels: &Labels,
) -> (BTreeMap<String, Mask>, Vec<(String, String)>) {
    let matched = assign_labels(plan, masks, labels);
    let out = matched
        .assigned
        .iter()
        .map(|(label, id)| (id.clone(), masks[label].clone()))
        .collect();
    let mut unmatched = matched.invisible;
    unmatched.extend(matched.unplanned.into_iter().map(|(id, category)| {
        let reason = format!(
            "labelled `{category}` in the guidance, but the plan holds no (further) {category} \
             for it (a re-plan dropped it, or the plan was full)"
        );
        (id, reason)
    }));
    (out, unmatched)
}

/// The structured answer the vision-language model must give.
pub fn boxes_schema() -> JsonSchema {
    JsonSchema::new(
        "object_boxes",
        json!({
            "type": "object",
            "additionalProperties": false,
            "required": ["objects"],
            "properties": {
                "objects": {
                    "type": "array",
                    "items": {
                        "type": "object",
                        "additionalProperties": false,
                        "required": ["id", "box"],
                        "properties": {
                            "id": {"type": "string", "minLength": 1},
                            "box": {
                                "type": "array",
                                "minItems": 4,
                                "maxItems": 4,
                                "items": {"type": "number", "minimum": 0, "maximum": 1}
                            }
                        }
                    }
                }
            }
        }),
    )
    .expect("the boxes schema is valid")
}

/// The request asking for one box per visible planned object.
pub fn boxes_request(plan: &Plan, image: ImageData, seed: u64) -> ChatRequest {
    let list: Vec<String> = plan
        .objects
        .iter()
        .map(|o| format!("- {}: {}", o.id, o.category.replace('_', " ")))
        .collect();
    let text = format!(
        "The image shows a {} ({}).\nFor every object of this list that you can see in the \
         image, give its id and its tight bounding box as [x_min, y_min, x_max, y_max] in \
         normalised image coordinates (0 to 1, origin at the top left). Leave out the objects \
         you cannot see; never guess a box for them.\n{}\nAnswer with JSON: {{\"objects\": \
         [{{\"id\": \"...\", \"box\": [x_min, y_min, x_max, y_max]}}, ...]}}.",
        plan.scene_type.replace('_', " "),
        plan.description,
        list.join("\n")
    );
    let mut request = ChatRequest::structured(
        vec![
            Message::system("You locate objects in photographs of rooms, precisely."),
            Message::user(text).with_image(image),
        ],
        boxes_schema(),
    );
    request.seed = Some(seed);
    request
}

/// Reads the model's answer: boxes of planned objects, by id (or, when the model answers with a
/// category, the first planned object of it not yet boxed). Boxes of unknown objects, repeated
/// ids and empty boxes are left out and said in the second list.
pub fn parse_boxes(plan: &Plan, answer: &Value) -> Boxes {
    let mut boxes: Vec<ObjectBox> = Vec::new();
    let mut notes = Vec::new();
    let items = answer
        .get("objects")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    for item in items {
        let name = item.get("id").and_then(Value::as_str).unwrap_or("");
        let coords: Vec<f32> = item
            .get("box")
            .and_then(Value::as_array)
            .map(|a| {
                a.iter()
                    .filter_map(Value::as_f64)
                    .map(|v| v as f32)
                    .collect()
            })
            .unwrap_or_default();
        let id = match plan.object(name) {
            Some(o) => Some(o.id.clone()),
            None => plan
                .objects
                .iter()
                .find(|o| o.category == name && !boxes.iter().any(|b| b.id == o.id))
                .map(|o| o.id.clone()),
        };
        let Some(id) = id else {
            notes.push((
                name.to_owned(),
                "the model boxed it but it is not planned".to_owned(),
            ));
            continue;
        };
        if boxes.iter().any(|b| b.id == id) {
            notes.push((
                id,
                "the model boxed it twice; the first box is kept".to_owned(),
            ));
            continue;
        }
        let [x0, y0, x1, y1] = coords[..] else {
            notes.push((id, "its box does not have 4 numbers".to_owned()));
            continue;
        };
        let ok = |v: f32| v.is_finite() && (0.0..=1.0).contains(&v);
        if !(ok(x0) && ok(y0) && ok(x1) && ok(y1)) || x1 <= x0 || y1 <= y0 {
            notes.push((
                id,
                format!("its box [{x0}, {y0}, {x1}, {y1}] is empty or outside [0, 1]"),
            ));
            continue;
        }
        boxes.push(ObjectBox {
            id,
            bbox: [x0, y0, x1, y1],
        });
    }
    (boxes, notes)
}

/// Boxes of planned objects, and `(name, why)` for each answer entry left out.
pub type Boxes = (Vec<ObjectBox>, Vec<(String, String)>);

/// Asks `vlm` for the boxes; the error names the model.
pub fn ask_boxes(
    vlm: &dyn ChatModel,
    plan: &Plan,
    image: ImageData,
    seed: u64,
) -> Result<Boxes, String> {
    let answer = vlm
        .chat(&boxes_request(plan, image, seed))
        .map_err(|e| e.to_string())?;
    let json = answer
        .json
        .ok_or_else(|| format!("{}: the answer holds no JSON", vlm.name()))?;
    Ok(parse_boxes(plan, &json))
}

/// The pixel rectangle `(x0, y0, x1, y1)` (exclusive ends) of a normalised box.
fn pixel_rect(bbox: [f32; 4], w: u32, h: u32) -> (u32, u32, u32, u32) {
    let px = |v: f32, n: u32| ((v as f64 * n as f64).round() as u32).min(n);
    let (x0, y0) = (px(bbox[0], w), px(bbox[1], h));
    let (x1, y1) = (
        px(bbox[2], w).max(x0 + 1).min(w),
        px(bbox[3], h).max(y0 + 1).min(h),
    );
    (x0, y0, x1, y1)
}

/// One mask per box. With a segmenter, its masks (checked to have the image's size); without,
/// the boxes themselves, where a pixel several boxes cover goes to the smallest box (a smaller
/// box overlapping a larger one is usually in front of it, or on it).
pub fn masks_from_boxes(
    boxes: &[ObjectBox],
    width: u32,
    height: u32,
    segmenter: Option<(&dyn Segmenter, &ImageData)>,
) -> Result<BTreeMap<String, Mask>, String> {
    let mut out = BTreeMap::new();
    if let Some((segmenter, image)) = segmenter {
        let prompts: Vec<BoxPrompt> = boxes
            .iter()
            .map(|b| BoxPrompt {
                label: b.id.clone(),
                bbox: b.bbox,
            })
            .collect();
        let masks = segmenter
            .segment(image, &prompts)
            .map_err(|e| e.to_string())?;
        if masks.len() != boxes.len() {
            return Err(format!(
                "{}: {} masks for {} boxes; expected one mask per box",
                segmenter.name(),
                masks.len(),
                boxes.len()
            ));
        }
        for (b, s) in boxes.iter().zip(masks) {
            if (s.mask.width(), s.mask.height()) != (width, height) {
                return Err(format!(
                    "{}: the mask of `{}` is {} × {} pixels; expected the image's {width} × {height}",
                    segmenter.name(),
                    b.id,
                    s.mask.width(),
                    s.mask.height()
                ));
            }
            out.insert(b.id.clone(), s.mask);
        }
        return Ok(out);
    }
    let rects: Vec<(u32, u32, u32, u32)> = boxes
        .iter()
        .map(|b| pixel_rect(b.bbox, width, height))
        .collect();
    let area = |r: &(u32, u32, u32, u32)| (r.2 - r.0) as u64 * (r.3 - r.1) as u64;
    for (i, b) in boxes.iter().enumerate() {
        let r = rects[i];
        let mut mask = Mask::new(width, height);
        for y in r.1..r.3 {
            for x in r.0..r.2 {
                let smaller_covers = rects.iter().enumerate().any(|(j, o)| {
                    j != i
                        && (area(o), j) < (area(&r), i)
                        && x >= o.0
                        && x < o.2
                        && y >= o.1
                        && y < o.3
                });
                if !smaller_covers {
                    mask.set(x, y, true);
                }
            }
        }
        out.insert(b.id.clone(), mask);
    }
    Ok(out)
}
