//! The support cross-check against a real HTTP model on 127.0.0.1: the vision-language model's
//! stated relations come back through the OpenAI-compatible client, an answer that flips an
//! ambiguous support is taken, and one that contradicts a clear support is overruled and noted.

use std::time::Duration;

use scenethesis_agents::{KnowledgePlanner, Plan, PlanRequest, Planner};
use scenethesis_models::ImageData;
use scenethesis_openai::testing::{openai_completion, Reply, TestServer};
use scenethesis_openai::{ClientConfig, OpenAiClient};
use scenethesis_vision::{infer_supports_within, Decision, LiftOptions, LiftedBox, LiftedScene};
use scenethesis_vision::{SupportGuess, SupportKind};
use scenethesis_vision_guide::relations::ask_supports;
use serde_json::json;

fn plan() -> Plan {
    let categories: std::collections::BTreeSet<String> =
        scenethesis_procedural::catalog::categories()
            .map(|c| c.name.to_string())
            .collect();
    KnowledgePlanner::new()
        .plan(&PlanRequest::new("a living room", categories, 0))
        .unwrap()
}

fn of<'a>(s: &'a [SupportGuess], id: &str) -> &'a SupportGuess {
    s.iter().find(|g| g.id == id).unwrap()
}

#[test]
fn the_models_answer_flips_an_ambiguous_support_and_not_a_clear_one() {
    // A table (top 0.75 m), a cabinet beside it, a lamp plainly on the table, and a frame
    // whose lifted box straddles the table's edge 10 cm above its top (the geometry reaches
    // for the table, marginally).
    let options = LiftOptions::default();
    let boxes = vec![
        LiftedBox::axis_aligned("table_0", [0.0, 0.375, 0.0], [0.6, 0.375, 0.4]),
        LiftedBox::axis_aligned("cabinet_0", [1.5, 0.45, 0.0], [0.3, 0.45, 0.3]),
        LiftedBox::axis_aligned("lamp_0", [0.1, 0.95, 0.0], [0.1, 0.2, 0.1]),
        LiftedBox::axis_aligned("frame_0", [0.65, 0.95, 0.0], [0.125, 0.1, 0.1]),
    ];
    let supports = infer_supports_within(&boxes, options.contact_gap, options.support_reach);
    assert_eq!(of(&supports, "frame_0").parent.as_deref(), Some("table_0"));
    let mut scene = LiftedScene {
        boxes,
        missing: vec![],
        supports,
        depth_scale: 1.0,
        depth_noise: 0.0,
    };
    let answer = json!({"supports": [
        {"id": "table_0", "relation": "floor", "parent": ""},
        {"id": "cabinet_0", "relation": "floor", "parent": ""},
        {"id": "lamp_0", "relation": "on", "parent": "cabinet_0"},
        {"id": "frame_0", "relation": "wall", "parent": ""}
    ]})
    .to_string();
    let server =
        TestServer::start(move |_, _| Reply::json(200, &openai_completion("eyes-1", &answer)));
    let mut config = ClientConfig::new(&server.base_url);
    config.vlm_model = Some("eyes-1".into());
    config.timeout = Duration::from_secs(5);
    config.max_attempts = 1;
    let vlm = OpenAiClient::new(config).unwrap().vlm().unwrap();
    let img = scenethesis_imagery::RgbImage::new(4, 4, vec![90; 48]).unwrap();
    let image = ImageData::from_bytes(img.to_png(), "png").unwrap();
    let ids = ["cabinet_0", "frame_0", "lamp_0", "table_0"];
    let objects = [
        ("cabinet_0", "cabinet"),
        ("frame_0", "picture_frame"),
        ("lamp_0", "table_lamp"),
        ("table_0", "table"),
    ];
    let (stated, skipped) = ask_supports(&vlm, &plan(), &objects, image, 0).unwrap();
    assert!(skipped.is_empty(), "{skipped:?}");
    let checks = scene.cross_check(&stated, &options);

    // One request, structured, with the image and every object listed.
    let requests = server.requests();
    assert_eq!(requests.len(), 1);
    let body = requests[0].json();
    assert_eq!(body["model"], "eyes-1");
    let sent = body.to_string();
    assert!(sent.contains("object_supports") && sent.contains("data:image/png;base64,"));
    assert!(ids.iter().all(|id| sent.contains(&format!("- {id}:"))));

    // The ambiguous frame: the model's wall mount is taken (unsupported, for the wall check).
    assert_eq!(
        of(&scene.supports, "frame_0").kind,
        SupportKind::Unsupported
    );
    // The clear lamp: geometry is kept, the disagreement is recorded.
    assert_eq!(
        (
            of(&scene.supports, "lamp_0").kind,
            of(&scene.supports, "lamp_0").parent.as_deref()
        ),
        (SupportKind::On, Some("table_0"))
    );
    assert_eq!(checks.len(), 2, "{checks:?}");
    let frame = checks.iter().find(|c| c.id == "frame_0").unwrap();
    assert_eq!(frame.decision, Decision::Model);
    let lamp = checks.iter().find(|c| c.id == "lamp_0").unwrap();
    assert_eq!(lamp.decision, Decision::Geometry);
    assert!(
        lamp.note().contains("the geometry is kept"),
        "{}",
        lamp.note()
    );
    // The lamp still rests on the table's top.
    let lamp_box = scene.boxes.iter().find(|b| b.id == "lamp_0").unwrap();
    assert!((lamp_box.bottom() - 0.75).abs() < 1e-9);
}
