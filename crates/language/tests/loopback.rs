//! The LLM planner against a model served over real HTTP on 127.0.0.1: a model's own plan for
//! "a pharmacy", a weak plan completed from offline knowledge, a detailed
//! prompt kept as written, and provider failures.

mod support;

use std::time::Duration;

use scenethesis_agents::{
    ConstraintTarget, Guide, KnowledgePlanner, Layer, NominalAssets, PlanError, PlanRequest,
    Planner, ProceduralGuide, Zone,
};
use scenethesis_language::LlmPlanner;
use scenethesis_models::UsageMeter;
use scenethesis_openai::{ClientConfig, OpenAiChat, OpenAiClient};
use scenethesis_scene_graph::{ParentRef, RelationKind};
use serde_json::{json, Value};
use support::{ollama_completion, openai_completion, vllm_completion, Reply, TestServer};

fn chat(server: &TestServer) -> OpenAiChat {
    let mut c = ClientConfig::new(&server.base_url);
    c.timeout = Duration::from_secs(5);
    c.max_attempts = 1;
    OpenAiClient::new(c).unwrap().chat("planner-model")
}

fn request(prompt: &str) -> PlanRequest {
    PlanRequest::new(prompt, KnowledgePlanner::new().known_categories(), 7)
}

/// An answer object; `place` is [support, parent, zone, wall].
fn obj(id: &str, category: &str, layer: &str, place: [&str; 4], relations: Value) -> Value {
    json!({"id": id, "category": category, "layer": layer, "support": place[0], "parent": place[1],
           "zone": place[2], "wall": place[3], "relations": relations, "stated": false})
}

/// A model's plan for "a pharmacy" (`fixtures/llm/pharmacy_plan.json`): chairs, bottles whose
/// parent is a shelf, and an x-ray machine the library does not have.
fn pharmacy() -> Value {
    serde_json::from_str(include_str!("../../../fixtures/llm/pharmacy_plan.json"))
        .expect("the pharmacy fixture is JSON")
}

#[test]
fn objects_the_prompt_names_and_the_model_left_out_are_added() {
    // The model plans its own pharmacy and ignores the mirror and two of the three chairs
    // the prompt asks for: the prompt is read offline (`requested`) and what the model left
    // out is added as the offline knowledge plans it, with a note.
    let mut clean = pharmacy();
    clean["objects"].as_array_mut().unwrap().pop();
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("gpt-4o", &clean.to_string()),
    )]);
    let planner = LlmPlanner::new(chat(&server));
    let plan = planner
        .plan(&request("a pharmacy with a mirror and three chairs"))
        .unwrap();
    let find = |words: &str| {
        plan.requested
            .iter()
            .find(|r| r.words == words)
            .unwrap_or_else(|| panic!("`{words}` is requested: {:?}", plan.requested))
    };
    let mirror = find("mirror");
    assert_eq!(mirror.count, 1, "{mirror:?}");
    assert_eq!(mirror.category.as_deref(), Some("mirror"));
    let chairs = find("chair");
    assert_eq!(chairs.count, 3);
    assert_eq!(chairs.ids[0], "chair_0", "the model's own chair counts");
    for r in [mirror, chairs] {
        assert_eq!(r.ids.len() as u32, r.count, "{r:?}");
        assert!(r.note.is_none(), "{r:?}");
        for id in &r.ids {
            assert!(plan.object(id).is_some(), "`{id}` is planned");
        }
    }
    assert!(
        plan.notes.iter().any(|n| n.contains("the model left out")),
        "{:?}",
        plan.notes
    );
}

#[test]
fn the_offline_planner_only_assumes_what_a_pharmacy_is() {
    // The offline planner reads "a pharmacy" through its thesaurus of places and says what it
    // assumed; the LLM planner below plans the model's own pharmacy instead.
    let offline = KnowledgePlanner::new()
        .plan(&request("a pharmacy"))
        .unwrap();
    assert!(
        !offline.assumptions.is_empty(),
        "the offline planner records what it assumed: {:?}",
        offline.notes
    );
}

#[test]
fn plans_a_pharmacy_from_an_openai_shaped_answer() {
    // The first answer names a category the library lacks: re-asked once, the second is clean.
    let first = pharmacy().to_string();
    let mut clean = pharmacy();
    clean["objects"].as_array_mut().unwrap().pop();
    let server = TestServer::scripted(vec![
        Reply::json(200, &openai_completion("gpt-4o", &first)),
        Reply::json(200, &openai_completion("gpt-4o", &clean.to_string())),
    ]);
    let model = chat(&server);
    let meter: UsageMeter = model.meter().clone();
    let planner = LlmPlanner::new(model);
    assert_eq!(planner.name(), "llm:openai-compatible/planner-model");
    let plan = planner.plan(&request("a pharmacy")).unwrap();
    assert_eq!(server.requests().len(), 2, "re-asked once");
    let again = server.requests()[1].json();
    let messages = again["messages"].as_array().unwrap();
    assert_eq!(
        messages[2]["content"],
        first.as_str(),
        "the previous answer is quoted"
    );
    assert!(messages[3]["content"]
        .as_str()
        .unwrap()
        .contains("`x-ray machine` (xray_0)"));
    assert_eq!(plan.scene_type, "pharmacy");
    assert_eq!(plan.anchor, "checkout_counter_0");
    assert_eq!(plan.objects[0].id, "checkout_counter_0");
    let completed = plan
        .notes
        .iter()
        .find_map(|n| n.split_once("whose core the model left out: "))
        .map_or(0, |(_, ids)| ids.split(", ").count());
    assert_eq!(
        plan.objects.len() - completed,
        18,
        "the x-ray machine is left out"
    );
    assert!(plan.objects.iter().all(|o| o.category != "x-ray machine"));
    // Nearest categories.
    assert_eq!(
        plan.object("cash_register_0").unwrap().category,
        "cash_register"
    );
    assert_eq!(plan.object("box_0").unwrap().category, "box");
    assert_eq!(plan.object("plant_0").unwrap().category, "plant");
    assert_eq!(plan.object("chair_0").unwrap().category, "chair");
    // Hierarchy and supports.
    let shelf = plan.object("store_shelf_0").unwrap();
    assert_eq!(
        (shelf.layer, shelf.support),
        (Layer::Background, RelationKind::AgainstWall)
    );
    assert_eq!(
        shelf.zone,
        Zone::Wall {
            wall: Some("wall_1".into())
        }
    );
    let bottle = plan.object("bottle_1").unwrap();
    assert_eq!(
        (bottle.support, &bottle.parent),
        (RelationKind::On, &ParentRef::Object("store_shelf_1".into()))
    );
    assert_eq!(bottle.zone, Zone::Supported);
    let basket = plan.object("shopping_basket_0").unwrap();
    assert_eq!(basket.relations[0].target, "checkout_counter_0");
    // Parents come before children.
    let pos = |id: &str| plan.objects.iter().position(|o| o.id == id).unwrap();
    assert!(pos("store_shelf_1") < pos("bottle_1") && pos("display_shelf_0") < pos("box_1"));
    assert!(plan.description.starts_with("Background: store shelves"));
    let notes = plan.notes.join("\n");
    assert!(
        notes.contains("re-asked once: these categories are not in the library"),
        "{notes}"
    );
    assert!(
        notes.contains("unavailable `prescription scanner`"),
        "{notes}"
    );
    assert!(
        notes.contains("`medicine boxes` (box_0) mapped to the nearest library category `box`"),
        "{notes}"
    );
    // The request carried the prompt, the categories and the schema.
    let sent = server.requests()[0].json();
    let user = sent["messages"][1]["content"].as_str().unwrap();
    assert!(
        user.contains("Prompt: a pharmacy") && user.contains("checkout_counter"),
        "{user}"
    );
    assert_eq!(sent["response_format"]["json_schema"]["name"], "scene_plan");
    assert_eq!(sent["response_format"]["json_schema"]["strict"], true);
    assert_eq!(sent["seed"], 7);
    assert_eq!(meter.snapshot().requests, 2);
    // The rest of the pipeline takes it as it takes an offline plan.
    let layout = ProceduralGuide::default()
        .layout(&plan, &NominalAssets::default(), 7)
        .unwrap();
    assert!(
        layout.scene.objects.len() >= 15,
        "{}",
        layout.scene.objects.len()
    );
}

fn weak_answer() -> Value {
    json!({
        "interpretation": "a living room",
        "detailed": false,
        "scene_type": "living room",
        "environment": "indoor",
        "room_width": 5.0,
        "room_depth": 4.0,
        "anchor": "hologram_0",
        "objects": [
            obj("sofa_0", "sofa", "middle", ["on-floor", "ground", "center", "any"], json!([])),
            obj("hologram_0", "hologram emitter", "middle", ["on-floor", "ground", "center", "any"], json!([])),
            obj("lamp_0", "floor lamp", "background", ["on-floor", "ground", "corner", "any"], json!([]))
        ],
        "unavailable": [],
        "description": "A sofa and a lamp."
    })
}

#[test]
fn a_weak_plan_is_reasked_once_then_completed_from_offline_knowledge() {
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &vllm_completion("Qwen/Qwen2.5-0.5B-Instruct", &weak_answer().to_string()),
    )]);
    let plan = LlmPlanner::new(chat(&server))
        .plan(&request("a cozy living room"))
        .unwrap();
    let requests = server.requests();
    assert_eq!(requests.len(), 2, "one re-ask");
    let critique = requests[1].json()["messages"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()["content"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(
        critique.contains("hologram emitter") && critique.contains("at least 15"),
        "{critique}"
    );
    assert!(plan.objects.len() >= 15, "{}", plan.objects.len());
    assert!(
        plan.object("sofa_0").is_some() && plan.object("floor_lamp_0").is_some(),
        "the model's objects stay"
    );
    let anchor = plan.object(&plan.anchor).unwrap();
    assert_eq!(anchor.parent, ParentRef::Ground);
    assert_eq!(plan.objects[0].id, plan.anchor);
    let categories = KnowledgePlanner::new().known_categories();
    assert!(plan
        .objects
        .iter()
        .all(|o| categories.contains(&o.category)));
    let ids: std::collections::BTreeSet<&str> =
        plan.objects.iter().map(|o| o.id.as_str()).collect();
    assert_eq!(ids.len(), plan.objects.len(), "ids stay unique");
    for o in &plan.objects {
        if let ParentRef::Object(p) = &o.parent {
            assert!(
                ids.contains(p.as_str()),
                "{} has a missing parent {p}",
                o.id
            );
        }
        for r in &o.relations {
            assert!(
                ids.contains(r.target.as_str()) || r.target.starts_with("wall_"),
                "{} -> {}",
                o.id,
                r.target
            );
        }
    }
    let notes = plan.notes.join("\n");
    assert!(
        notes.contains("re-asked once") && notes.contains("completed from offline knowledge"),
        "{notes}"
    );
    ProceduralGuide::default()
        .layout(&plan, &NominalAssets::default(), 7)
        .unwrap();
}

#[test]
fn a_detailed_prompt_keeps_what_the_user_stated() {
    let prompt = "a study with a desk against the back wall, an office chair in front of the desk and a bookshelf beside the desk";
    let mut chair = obj(
        "office_chair_0",
        "office_chair",
        "foreground",
        ["on-floor", "ground", "relative", "any"],
        json!([{"kind": "in-front-of", "target": "desk_0"}]),
    );
    chair["stated"] = json!(true);
    let mut desk = obj(
        "desk_0",
        "desk",
        "middle",
        ["against-wall", "ground", "wall", "wall_0"],
        json!([]),
    );
    desk["stated"] = json!(true);
    let mut shelf = obj(
        "bookshelf_0",
        "bookshelf",
        "background",
        ["against-wall", "ground", "wall", "any"],
        json!([{"kind": "beside", "target": "desk_0"}]),
    );
    shelf["stated"] = json!(true);
    let answer = json!({
        "interpretation": "a small study", "detailed": true, "scene_type": "study", "environment": "indoor",
        "room_width": 4.0, "room_depth": 3.5, "anchor": "desk_0",
        "objects": [desk, chair, shelf, obj("laptop_0", "laptop", "middle", ["on", "desk_0", "supported", "any"], json!([]))],
        "unavailable": [], "description": "ignored for a detailed prompt"
    });
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &ollama_completion("llama3.1:8b", &answer.to_string()),
    )]);
    let plan = LlmPlanner::new(chat(&server))
        .plan(&request(prompt))
        .unwrap();
    assert_eq!(
        server.requests().len(),
        1,
        "a detailed prompt needs no 15 objects"
    );
    assert_eq!(
        plan.description, prompt,
        "a detailed prompt is not up-sampled"
    );
    assert_eq!(plan.objects.len(), 4, "{:?}", plan.notes);
    let has = |subject: &str, kind: RelationKind, target: ConstraintTarget| {
        plan.constraints
            .iter()
            .any(|c| c.subject == subject && c.kind == kind && c.target == target)
    };
    assert!(
        has(
            "desk_0",
            RelationKind::AgainstWall,
            ConstraintTarget::Wall("wall_0".into())
        ),
        "{:?}",
        plan.constraints
    );
    assert!(has(
        "office_chair_0",
        RelationKind::InFrontOf,
        ConstraintTarget::Object("desk_0".into())
    ));
    assert!(has(
        "bookshelf_0",
        RelationKind::Beside,
        ConstraintTarget::Object("desk_0".into())
    ));
    assert!(has(
        "bookshelf_0",
        RelationKind::AgainstWall,
        ConstraintTarget::AnyWall
    ));
    assert!(plan
        .objects
        .iter()
        .filter(|o| o.id != "laptop_0")
        .all(|o| o.hard));
}

#[test]
fn garbage_after_the_repair_round_is_planned_offline_with_a_note() {
    // No JSON even after the client's repair round and the planner's re-ask: the offline
    // knowledge plans it, and the plan says why.
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("m", "I am a small model and I like rooms."),
    )]);
    let plan = LlmPlanner::new(chat(&server))
        .plan(&request("a cozy living room"))
        .unwrap();
    assert_eq!(
        server.requests().len(),
        4,
        "answer and repair round, twice (the planner re-asks once)"
    );
    assert!(
        plan.notes.iter().any(|n| n.contains("unusable twice")),
        "{:?}",
        plan.notes
    );

    // A server answering something that is not a chat completion at all: a provider error.
    let server = TestServer::scripted(vec![Reply::raw(200, "text/html", "<html>gateway</html>")]);
    let err = LlmPlanner::new(chat(&server))
        .plan(&request("a pharmacy"))
        .unwrap_err();
    let PlanError::Provider { provider, message } = &err else {
        panic!("{err}")
    };
    assert_eq!(provider, "llm:openai-compatible/planner-model");
    assert!(message.contains("(model `planner-model`)"), "{message}");
    assert!(message.contains("malformed"), "{message}");
    assert!(err.to_string().contains("<html>gateway</html>"), "{err}");

    // Schema-violating JSON twice (answer and repair): completed from offline knowledge
    // without re-asking, saying what was wrong.
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("m", r#"{"objects": 3}"#),
    )]);
    let plan = LlmPlanner::new(chat(&server))
        .plan(&request("a pharmacy"))
        .unwrap();
    assert_eq!(
        server.requests().len(),
        2,
        "answer and the client's repair round"
    );
    let notes = plan.notes.join("\n");
    assert!(notes.contains("violates the JSON schema"), "{notes}");
    assert!(
        notes.contains("completed from offline knowledge"),
        "{notes}"
    );
    assert!(
        plan.objects.len() >= scenethesis_language::MIN_OBJECTS,
        "{notes}"
    );
}

/// A completion cut off by `max_tokens` (`finish_reason: length`) in OpenAI's shape.
fn cut_off(content: &str) -> Value {
    let mut c = openai_completion("small-model", content);
    c["choices"][0]["finish_reason"] = json!("length");
    c
}

#[test]
fn every_plan_request_states_max_tokens() {
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("m", &pharmacy().to_string()),
    )]);
    let _ = LlmPlanner::new(chat(&server)).plan(&request("a pharmacy"));
    let requests = server.requests();
    assert!(!requests.is_empty());
    for r in requests {
        assert_eq!(
            r.json()["max_tokens"],
            json!(scenethesis_language::plan_max_tokens())
        );
    }
    assert_eq!(
        scenethesis_language::plan_max_tokens(),
        scenethesis_language::PLAN_OVERHEAD_TOKENS
            + scenethesis_language::TOKENS_PER_OBJECT
                * scenethesis_language::MAX_ANSWER_OBJECTS as u32
    );
}

#[test]
fn a_cut_off_answer_keeps_its_complete_objects_and_is_completed_offline() {
    // A weak local model's answer (issue 20): cut off mid-object, a nonsense category, an
    // object that is its own parent. It is not re-asked (a repair would be cut off too).
    let mut answer = pharmacy();
    let objects = answer["objects"].as_array_mut().unwrap();
    objects.truncate(4);
    objects.push(obj(
        "a3210548967_0",
        "a3210548967",
        "middle",
        ["on-floor", "ground", "free", "any"],
        json!([]),
    ));
    objects.push(obj(
        "vase_9",
        "vase",
        "foreground",
        ["on", "vase_9", "supported", "any"],
        json!([]),
    ));
    objects.push(obj(
        "chair_7",
        "chair",
        "middle",
        ["on-floor", "ground", "free", "any"],
        json!([]),
    ));
    let text = answer.to_string();
    let cut = text.find("\"chair_7\"").unwrap() + 20;
    let server = TestServer::scripted(vec![Reply::json(200, &cut_off(&text[..cut]))]);
    let plan = LlmPlanner::new(chat(&server))
        .plan(&request("a pharmacy"))
        .unwrap();
    assert_eq!(
        server.requests().len(),
        1,
        "a cut-off answer is not re-asked"
    );
    let notes = plan.notes.join("\n");
    assert!(notes.contains("cut off at max_tokens"), "{notes}");
    assert!(
        notes.contains("a3210548967"),
        "the dropped category is named: {notes}"
    );
    assert!(notes.contains("vase_9: rests on itself"), "{notes}");
    assert!(
        notes.contains("completed from offline knowledge"),
        "{notes}"
    );
    // The four complete objects of the model are kept; the partial one is not.
    for o in &pharmacy()["objects"].as_array().unwrap()[..4] {
        let id = o["id"].as_str().unwrap();
        assert!(
            plan.object(id).is_some() || notes.contains(id),
            "{id}: {notes}"
        );
    }
    assert!(plan.object("chair_7").is_none(), "{notes}");
    assert_eq!(plan.object("vase_9").unwrap().parent, ParentRef::Ground);
    assert!(plan.objects.len() >= scenethesis_language::MIN_OBJECTS);
    scenethesis_agents::check_plan(&plan, Some(&request("a pharmacy").available_categories))
        .unwrap();
}

#[test]
fn ids_the_scene_validator_refuses_are_renamed_with_a_note() {
    let mut answer = pharmacy();
    answer["objects"].as_array_mut().unwrap().pop();
    answer["objects"][0]["id"] = json!("evil\u{1b}[2J\u{202e}");
    answer["objects"][1]["id"] = json!("x".repeat(10_000));
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("m", &answer.to_string()),
    )]);
    let plan = LlmPlanner::new(chat(&server))
        .plan(&request("a pharmacy"))
        .unwrap();
    for o in &plan.objects {
        assert!(
            scenethesis_scene_graph::is_printable_id(&o.id),
            "{:?}",
            o.id
        );
    }
    let notes = plan.notes.join("\n");
    assert!(notes.contains("cannot be written to scene.json"), "{notes}");
    assert!(
        !notes.contains('\u{1b}') && !notes.contains('\u{202e}'),
        "{notes}"
    );
    assert!(
        !notes.contains(&"x".repeat(100)),
        "the long id is shortened"
    );
    scenethesis_agents::check_plan(&plan, None).unwrap();
}

#[test]
fn an_oversized_answer_is_capped_live_and_on_replay_alike() {
    use scenethesis_models::{CacheMode, Cached, ResponseCache};
    let mut answer = pharmacy();
    let template = answer["objects"][0].clone();
    let objects = answer["objects"].as_array_mut().unwrap();
    for k in 0..10_001 {
        let mut o = template.clone();
        o["id"] = json!(format!("extra_{k}"));
        objects.push(o);
    }
    let dir = tempfile::tempdir().unwrap();
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("m", &answer.to_string()),
    )]);
    let live = Cached::new(
        chat(&server),
        ResponseCache::open(dir.path(), CacheMode::ReadWrite).unwrap(),
    );
    let live = LlmPlanner::new(live).plan(&request("a pharmacy")).unwrap();
    assert!(live.objects.len() <= scenethesis_agents::MAX_PLANNED_OBJECTS);
    let notes = live.notes.join("\n");
    assert!(notes.contains("MAX_ANSWER_OBJECTS"), "{notes}");
    // Replayed from the cache, offline: the same check, the same plan.
    let replay = Cached::new(
        OpenAiClient::new(ClientConfig::new("http://127.0.0.1:9/v1"))
            .unwrap()
            .chat("planner-model"),
        ResponseCache::open(dir.path(), CacheMode::ReplayOnly).unwrap(),
    );
    let replayed = LlmPlanner::new(replay)
        .plan(&request("a pharmacy"))
        .unwrap();
    assert_eq!(
        serde_json::to_string(&replayed).unwrap(),
        serde_json::to_string(&live).unwrap()
    );
}

#[test]
fn a_hand_made_cache_entry_gets_the_live_schema_check() {
    // A cache entry written by hand (or by another tool) holding 10 001 objects, as the
    // issue's replay case: capped exactly as a live answer is.
    use scenethesis_models::{CacheMode, Cached, ChatModel, ChatRequest, ResponseCache};
    let dir = tempfile::tempdir().unwrap();
    let model = OpenAiClient::new(ClientConfig::new("http://127.0.0.1:9/v1"))
        .unwrap()
        .chat("planner-model");
    let name = model.name();
    let mut answer = pharmacy();
    let template = answer["objects"][0].clone();
    answer["objects"] = json!((0..10_001)
        .map(|k| {
            let mut o = template.clone();
            o["id"] = json!(format!("extra_{k}"));
            o
        })
        .collect::<Vec<_>>());
    // Record what the planner will ask, by asking once through a recording model.
    struct Recorder(std::sync::Mutex<Option<ChatRequest>>, String);
    impl ChatModel for Recorder {
        fn name(&self) -> String {
            self.1.clone()
        }
        fn chat(
            &self,
            r: &ChatRequest,
        ) -> Result<scenethesis_models::ChatResponse, scenethesis_models::ProviderError> {
            *self.0.lock().unwrap() = Some(r.clone());
            Err(scenethesis_models::ProviderError::new(
                "x",
                "m",
                scenethesis_models::ProviderErrorKind::Unsupported {
                    operation: "recording".into(),
                },
            ))
        }
    }
    let recorder = Recorder(Default::default(), name.clone());
    let _ = LlmPlanner::new(&recorder).plan(&request("a pharmacy"));
    let asked = recorder.0.lock().unwrap().clone().unwrap();
    let cache = ResponseCache::open(dir.path(), CacheMode::ReadWrite).unwrap();
    let response = scenethesis_models::ChatResponse {
        text: answer.to_string(),
        json: Some(answer.clone()),
        model: "m".into(),
        usage: Default::default(),
        notes: vec![],
    };
    cache.put("chat", &name, &asked, &response).unwrap();
    let replay = Cached::new(
        model,
        ResponseCache::open(dir.path(), CacheMode::ReplayOnly).unwrap(),
    );
    let plan = LlmPlanner::new(replay)
        .plan(&request("a pharmacy"))
        .unwrap();
    assert!(plan.objects.len() <= scenethesis_agents::MAX_PLANNED_OBJECTS);
    let notes = plan.notes.join("\n");
    assert!(notes.contains("violates the schema"), "{notes}");
    assert!(notes.contains("MAX_ANSWER_OBJECTS"), "{notes}");
}

#[test]
fn a_key_in_the_model_text_does_not_reach_the_plan() {
    const KEY: &str = "sk-test-SECRET-0123456789";
    let mut answer = pharmacy();
    answer["objects"].as_array_mut().unwrap().pop();
    answer["interpretation"] = json!(format!("the key is {KEY}"));
    answer["unavailable"] = json!([{"name": KEY, "reason": format!("because {KEY}")}]);
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("m", &answer.to_string()),
    )]);
    let mut c = ClientConfig::new(&server.base_url);
    c.max_attempts = 1;
    c.api_key = Some(scenethesis_openai::ApiKey::new(KEY.to_string()));
    let model = OpenAiClient::new(c).unwrap().chat("planner-model");
    let plan = LlmPlanner::new(model).plan(&request("a pharmacy")).unwrap();
    let json = serde_json::to_string(&plan).unwrap();
    assert!(!json.contains(KEY), "{json}");
    assert!(json.contains("the key is ***"), "{json}");
}

#[test]
fn provider_failures_are_errors_naming_the_endpoint() {
    let server = TestServer::scripted(vec![Reply::json(
        503,
        &json!({"error": {"message": "model is loading"}}),
    )]);
    let err = LlmPlanner::new(chat(&server))
        .plan(&request("a pharmacy"))
        .unwrap_err();
    let PlanError::Provider { provider, message } = &err else {
        panic!("{err}")
    };
    assert_eq!(provider, "llm:openai-compatible/planner-model");
    assert!(
        message.contains(&format!(
            "{}/chat/completions (model `planner-model`): HTTP 503: model is loading",
            server.base_url
        )),
        "{message}"
    );
    let refused = {
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let mut c = ClientConfig::new(format!("http://127.0.0.1:{port}/v1"));
        c.max_attempts = 1;
        OpenAiClient::new(c).unwrap().chat("m")
    };
    let err = LlmPlanner::new(refused)
        .plan(&request("a pharmacy"))
        .unwrap_err();
    assert!(
        err.to_string().contains("the server is unreachable"),
        "{err}"
    );
    assert_eq!(
        LlmPlanner::new(chat(&server))
            .plan(&request("  "))
            .unwrap_err(),
        PlanError::EmptyPrompt
    );
}

#[test]
fn a_cached_planner_replays_the_same_plan_offline() {
    use scenethesis_models::{CacheMode, Cached, ResponseCache};
    let dir = std::env::temp_dir().join(format!("language-cache-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut clean = pharmacy();
    clean["objects"].as_array_mut().unwrap().pop();
    let recorded = {
        let server = TestServer::scripted(vec![Reply::json(
            200,
            &openai_completion("gpt-4o", &clean.to_string()),
        )]);
        let model = Cached::new(
            chat(&server),
            ResponseCache::open(&dir, CacheMode::ReadWrite).unwrap(),
        );
        LlmPlanner::new(model).plan(&request("a pharmacy")).unwrap()
    };
    let offline = ClientConfig::new("http://127.0.0.1:9/v1");
    let model = Cached::new(
        OpenAiClient::new(offline).unwrap().chat("planner-model"),
        ResponseCache::open(&dir, CacheMode::ReplayOnly).unwrap(),
    );
    let replayed = LlmPlanner::new(model).plan(&request("a pharmacy")).unwrap();
    assert_eq!(
        serde_json::to_string(&replayed).unwrap(),
        serde_json::to_string(&recorded).unwrap()
    );
    // Another seed is another request: not in the cache, and replay-only says so.
    let model = Cached::new(
        OpenAiClient::new(ClientConfig::new("http://127.0.0.1:9/v1"))
            .unwrap()
            .chat("planner-model"),
        ResponseCache::open(&dir, CacheMode::ReplayOnly).unwrap(),
    );
    let mut other = request("a pharmacy");
    other.seed = 8;
    let err = LlmPlanner::new(model).plan(&other).unwrap_err();
    assert!(err.to_string().contains("no cached answer"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_planner_is_send_and_sync() {
    fn check<T: Send + Sync>() {}
    check::<LlmPlanner<OpenAiChat>>();
    check::<LlmPlanner<scenethesis_models::Cached<OpenAiChat>>>();
}

/// Records how much of each stage's model answer had arrived.
#[derive(Default)]
struct Heard(std::rc::Rc<std::cell::RefCell<Vec<(scenethesis_pipeline::Stage, usize)>>>);

impl scenethesis_pipeline::Progress for Heard {
    fn answer_listener(
        &mut self,
        stage: scenethesis_pipeline::Stage,
        _round: usize,
    ) -> Option<scenethesis_models::AnswerListener> {
        let sink = std::rc::Rc::clone(&self.0);
        Some(Box::new(move |p: &scenethesis_models::AnswerProgress| {
            sink.borrow_mut().push((stage, p.characters))
        }))
    }
}

#[test]
fn a_streamed_plan_shows_progress_and_one_that_stalls_is_salvaged() {
    // The pharmacy plan as a slow local model streams it: 40 characters a piece, then a
    // stall past the request's timeout two thirds of the way through.
    let text = include_str!("../../../fixtures/llm/pharmacy_plan.json");
    let pieces: Vec<String> = text
        .chars()
        .collect::<Vec<_>>()
        .chunks(40)
        .map(|c| c.iter().collect())
        .collect();
    let refs: Vec<&str> = pieces.iter().map(String::as_str).collect();
    let events = support::openai_stream("small-model", &refs);
    let stall_at = events.len() * 2 / 3;
    let server = TestServer::scripted(vec![
        Reply::events(events, Duration::ZERO).stall_before(stall_at, Duration::from_secs(4))
    ]);
    let mut c = ClientConfig::new(&server.base_url);
    c.timeout = Duration::from_millis(800);
    c.max_attempts = 2;
    let planner = LlmPlanner::new(OpenAiClient::new(c).unwrap().chat("small-model"));
    let heard = Heard::default();
    let log = std::rc::Rc::clone(&heard.0);
    let mut progress = heard;
    let generated = scenethesis_pipeline::Pipeline::offline()
        .with_planner(planner)
        .generate(
            "a pharmacy",
            0,
            &scenethesis_pipeline::GenerateOptions {
                previews: false,
                ..Default::default()
            },
            &mut progress,
        )
        .unwrap();
    assert_eq!(server.requests().len(), 1, "the part received is used");
    assert_eq!(server.requests()[0].json()["stream"], true);
    let received = (stall_at - 1) * 40;
    let log = log.borrow();
    assert!(!log.is_empty());
    assert!(log
        .iter()
        .all(|(s, _)| *s == scenethesis_pipeline::Stage::Plan));
    assert_eq!(log.last().unwrap().1, received, "{log:?}");
    let notes = generated.plan.notes.join("\n");
    assert!(
        notes.contains(&format!(
            "timed out after 0.8 s with {} characters of the answer received",
            scenethesis_models::grouped(received)
        )),
        "{notes}"
    );
    assert!(notes.contains("salvaged"), "{notes}");
    assert!(
        generated.plan.object("checkout_counter_0").is_some(),
        "{notes}"
    );
    assert!(generated.plan.objects.len() >= scenethesis_language::MIN_OBJECTS);
}

#[test]
fn the_models_reading_is_used_and_completed_from_the_same_knowledge() {
    // The model reads the prompt as a home cinema but plans only a sofa: its reading stays,
    // and what any home cinema holds (the knowledge's core for it) is added with a note.
    let answer = json!({
        "interpretation": "a small home cinema", "detailed": false, "scene_type": "home cinema",
        "environment": "indoor", "room_width": 5.0, "room_depth": 4.5, "anchor": "sofa_0",
        "objects": [obj("sofa_0", "sofa", "middle", ["against-wall", "ground", "wall", "wall_0"], json!([]))],
        "unavailable": [], "description": "A sofa."
    });
    // A plan this small is weak: re-asked once, the same answer comes back.
    let reply = || Reply::json(200, &openai_completion("gpt-4o", &answer.to_string()));
    let server = TestServer::scripted(vec![reply(), reply()]);
    let plan = LlmPlanner::new(chat(&server))
        .plan(&request("a home cinema with a sofa"))
        .unwrap();
    assert_eq!(plan.scene_type, "home_cinema");
    let reading = plan
        .reading
        .clone()
        .expect("the model's reading is recorded");
    assert_eq!(reading.source, scenethesis_agents::ReadingSource::Model);
    assert!(!reading.is_low(), "{reading:?}");
    let core = KnowledgePlanner::new().core_of("home_cinema");
    assert!(!core.is_empty());
    let categories = plan.categories();
    for c in &core {
        assert!(
            categories.contains(c.as_str()),
            "core `{c}` missing: {categories:?}"
        );
    }
    assert!(
        plan.notes
            .iter()
            .any(|n| n.starts_with("completed the model's `home_cinema`")),
        "{:?}",
        plan.notes
    );
    assert!(plan.object("sofa_0").is_some(), "the model's objects stay");
}
