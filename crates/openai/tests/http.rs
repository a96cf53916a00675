//! The clients against real HTTP on 127.0.0.1: answers in the shapes of OpenAI, vLLM, Ollama
//! and llama.cpp, format fallbacks, and the failures (malformed and schema-violating answers,
//! 429 with Retry-After, 500, slow replies, refused connections).

mod support;

use std::time::{Duration, Instant};

use scenethesis_models::{
    CacheMode, Cached, ChatModel, ChatRequest, ImageData, ImageEditRequest, ImageGenerator,
    ImageRequest, JsonSchema, Message, ProviderErrorKind, ResponseCache, TextEmbedder,
};
use scenethesis_openai::{
    ApiKey, ClientConfig, OpenAiClient, OutputFormat, Overrides, ServerKind, ENV_SERVER,
};
use serde_json::{json, Value};
use support::{
    llamacpp_completion, ollama_completion, openai_completion, png, vllm_completion, Reply,
    TestServer,
};

const KEY: &str = "sk-test-DO-NOT-LEAK-1234";

fn config(server: &TestServer) -> ClientConfig {
    let mut c = ClientConfig::new(&server.base_url);
    c.api_key = Some(ApiKey::new(KEY));
    c.timeout = Duration::from_secs(5);
    c.backoff = Duration::from_millis(20);
    c.max_attempts = 3;
    c.budget = Duration::from_secs(20);
    c
}

fn client(server: &TestServer) -> OpenAiClient {
    OpenAiClient::new(config(server)).unwrap()
}

/// The schema of a small room listing: closed objects, every property required (strict-ready).
fn room_schema() -> JsonSchema {
    JsonSchema::new(
        "room_objects",
        json!({
            "type": "object",
            "additionalProperties": false,
            "required": ["anchor", "objects"],
            "properties": {
                "anchor": {"type": "string", "minLength": 1},
                "objects": {
                    "type": "array",
                    "minItems": 2,
                    "items": {
                        "type": "object",
                        "additionalProperties": false,
                        "required": ["category", "count"],
                        "properties": {
                            "category": {"type": "string"},
                            "count": {"type": "integer", "minimum": 1, "maximum": 50}
                        }
                    }
                }
            }
        }),
    )
    .unwrap()
}

const GOOD: &str = r#"{"anchor":"counter","objects":[{"category":"counter","count":1},{"category":"shelf","count":6}]}"#;

fn request() -> ChatRequest {
    ChatRequest::structured(
        vec![
            Message::system("You plan rooms."),
            Message::user("List the objects of a pharmacy."),
        ],
        room_schema(),
    )
}

fn assert_no_key(text: &str) {
    assert!(!text.contains(KEY), "the API key leaked: {text}");
}

#[test]
fn openai_shape_uses_strict_json_schema_and_bearer_key() {
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("gpt-4o-2024-08-06", GOOD),
    )]);
    let chat = client(&server).chat("gpt-4o");
    let answer = chat.chat(&request()).unwrap();
    assert_eq!(answer.json.as_ref().unwrap()["objects"][1]["count"], 6);
    assert_eq!(answer.model, "gpt-4o-2024-08-06");
    assert_eq!(
        (answer.usage.prompt_tokens, answer.usage.completion_tokens),
        (120, 30)
    );
    assert!(answer.notes.is_empty());

    let requests = server.requests();
    assert_eq!(requests.len(), 1);
    let r = &requests[0];
    assert_eq!(
        (r.method.as_str(), r.path.as_str()),
        ("POST", "/v1/chat/completions")
    );
    assert_eq!(
        r.header("authorization"),
        Some(format!("Bearer {KEY}").as_str())
    );
    let body = r.json();
    assert_eq!(body["model"], "gpt-4o");
    assert_eq!(body["temperature"], 0.0);
    assert_eq!(body["response_format"]["type"], "json_schema");
    assert_eq!(
        body["response_format"]["json_schema"]["name"],
        "room_objects"
    );
    assert_eq!(body["response_format"]["json_schema"]["strict"], true);
    assert_eq!(
        body["messages"][0],
        json!({"role": "system", "content": "You plan rooms."})
    );
    let usage = chat.meter().snapshot();
    assert_eq!(
        (usage.requests, usage.prompt_tokens, usage.completion_tokens),
        (1, 120, 30)
    );
    assert_no_key(&format!("{chat:?} {usage:?}"));
}

#[test]
fn vllm_and_ollama_shapes_with_an_image_part() {
    let photo = ImageData::from_bytes(png(4, 3, [200, 10, 10]), "photo").unwrap();
    for (shape, body) in [
        ("vllm", vllm_completion("Qwen/Qwen2.5-VL-7B-Instruct", GOOD)),
        ("ollama", ollama_completion("llava:13b", GOOD)),
    ] {
        let server = TestServer::scripted(vec![Reply::json(200, &body)]);
        let chat = client(&server).chat("vision");
        let mut req = request();
        req.messages[1] =
            Message::user("What is in this pharmacy photo?").with_image(photo.clone());
        let answer = chat.chat(&req).unwrap();
        assert_eq!(answer.json.unwrap()["anchor"], "counter", "{shape}");
        let sent = server.requests()[0].json();
        let parts = &sent["messages"][1]["content"];
        assert_eq!(parts[0]["type"], "text", "{shape}");
        assert_eq!(parts[1]["type"], "image_url", "{shape}");
        let url = parts[1]["image_url"]["url"].as_str().unwrap();
        assert_eq!(
            ImageData::from_data_url(url, "sent").unwrap(),
            photo,
            "{shape}"
        );
    }
}

#[test]
fn a_vllm_server_gets_structured_outputs_and_others_do_not() {
    for (server_kind, expect_extra) in [(ServerKind::Vllm, true), (ServerKind::default(), false)] {
        let server = TestServer::scripted(vec![Reply::json(200, &vllm_completion("m", GOOD))]);
        let mut c = config(&server);
        c.server = server_kind;
        let chat = OpenAiClient::new(c).unwrap().chat("m");
        chat.chat(&request()).unwrap();
        let sent = server.requests()[0].json();
        assert_eq!(sent["response_format"]["type"], "json_schema");
        if expect_extra {
            assert_eq!(
                sent["structured_outputs"]["json"],
                room_schema().schema,
                "vLLM constrains decoding with structured_outputs"
            );
        } else {
            assert!(sent.get("structured_outputs").is_none(), "{sent}");
        }
    }
    // Chosen by name in the environment or the config file; a wrong name is an error naming
    // the field.
    let env = |name: &str| (name == ENV_SERVER).then(|| "vLLM".to_owned());
    let c = ClientConfig::resolve_with(&Overrides::default(), &env, None).unwrap();
    assert_eq!(c.server, ServerKind::Vllm);
    let env = |name: &str| (name == ENV_SERVER).then(|| "tgi".to_owned());
    let err = ClientConfig::resolve_with(&Overrides::default(), &env, None).unwrap_err();
    assert!(err.to_string().contains("server"), "{err}");
}

#[test]
fn llama_cpp_python_500_on_json_schema_falls_back_to_json_object_and_remembers() {
    // llama-cpp-python rejects `json_schema` with a 500 and a validation message; it accepts
    // `json_object` with a `schema`, which it enforces.
    let server = TestServer::start(|_, r| {
        let body = r.json();
        if body["response_format"]["type"] == "json_schema" {
            Reply::json(
                500,
                &json!({"error": {"message": "1 validation error for CreateChatCompletionRequest\nresponse_format\n  Input should be 'text' or 'json_object'", "type": "internal_server_error"}}),
            )
        } else {
            Reply::json(
                200,
                &llamacpp_completion(
                    "qwen2.5-7b-instruct-q4_k_m.gguf",
                    &format!("```json\n{GOOD}\n```"),
                ),
            )
        }
    });
    let chat = client(&server).chat("local");
    let first = chat.chat(&request()).unwrap();
    assert_eq!(first.json.unwrap()["objects"][0]["category"], "counter");
    assert_eq!(first.notes.len(), 1);
    assert!(
        first.notes[0].contains("json_schema") && first.notes[0].contains("HTTP 500"),
        "{:?}",
        first.notes
    );
    let requests = server.requests();
    assert_eq!(requests.len(), 2, "a format rejection is not retried");
    let fallback = requests[1].json();
    assert_eq!(fallback["response_format"]["type"], "json_object");
    assert_eq!(
        fallback["response_format"]["schema"]["required"],
        json!(["anchor", "objects"])
    );
    assert!(fallback["messages"][0]["content"]
        .as_str()
        .unwrap()
        .contains("room_objects"));
    // Later calls start with the format that worked.
    assert_eq!(chat.first_format(), OutputFormat::JsonObject);
    chat.chat(&request()).unwrap();
    assert_eq!(server.requests().len(), 3);
}

#[test]
fn falls_back_to_a_plain_instruction_and_extracts_wrapped_json() {
    let server = TestServer::start(|_, r| {
        let body = r.json();
        match body["response_format"]["type"].as_str() {
            Some("json_schema") => Reply::json(
                400,
                &json!({"error": "response_format json_schema is not supported"}),
            ),
            Some(_) => Reply::json(422, &json!({"detail": "json_object not supported"})),
            None => Reply::json(
                200,
                &ollama_completion(
                    "tiny",
                    &format!("Sure! Here is the list:\n{GOOD}\nHope this helps."),
                ),
            ),
        }
    });
    let answer = client(&server).chat("tiny").chat(&request()).unwrap();
    assert_eq!(answer.json.unwrap()["anchor"], "counter");
    assert_eq!(answer.notes.len(), 2);
    let requests = server.requests();
    assert_eq!(requests.len(), 3);
    assert!(requests[2].json().get("response_format").is_none());
}

#[test]
fn schema_violation_gets_one_repair_round_quoting_the_error() {
    let bad =
        r#"{"anchor":"counter","objects":[{"category":"counter","count":0},{"category":"shelf"}]}"#;
    let server = TestServer::scripted(vec![
        Reply::json(200, &openai_completion("m", bad)),
        Reply::json(200, &openai_completion("m", GOOD)),
    ]);
    let answer = client(&server).chat("m").chat(&request()).unwrap();
    assert_eq!(answer.json.unwrap()["objects"][1]["count"], 6);
    assert_eq!(
        (answer.usage.prompt_tokens, answer.usage.completion_tokens),
        (240, 60)
    );
    assert!(
        answer.notes[0].starts_with("answer repaired once"),
        "{:?}",
        answer.notes
    );
    let repair = server.requests()[1].json();
    let messages = repair["messages"].as_array().unwrap();
    assert_eq!(messages[messages.len() - 2]["content"], bad);
    let quote = messages.last().unwrap()["content"].as_str().unwrap();
    assert!(
        quote.contains("at /objects/0/count: expected at least 1, found 0"),
        "{quote}"
    );
    assert!(
        quote.contains("at /objects/1: missing required property `count`"),
        "{quote}"
    );
}

#[test]
fn schema_violating_twice_is_an_error_naming_endpoint_model_and_path() {
    let bad = r#"{"anchor":"counter","objects":[{"category":"counter","count":"one"},{"category":"shelf","count":2}]}"#;
    let server = TestServer::scripted(vec![Reply::json(200, &vllm_completion("m", bad))]);
    let err = client(&server)
        .chat("planner-7b")
        .chat(&request())
        .unwrap_err();
    assert!(
        matches!(&err.kind, ProviderErrorKind::Schema { violation, .. } if violation.path == "/objects/0/count")
    );
    let text = err.to_string();
    assert!(
        text.starts_with(&format!(
            "{}/chat/completions (model `planner-7b`)",
            server.base_url
        )),
        "{text}"
    );
    assert!(
        text.contains("expected integer, found string \"one\""),
        "{text}"
    );
    assert_eq!(server.requests().len(), 2, "exactly one repair round");
    assert_no_key(&text);
}

#[test]
fn malformed_json_answers_are_clear_errors() {
    // A body that is not JSON at all.
    let server = TestServer::scripted(vec![Reply::raw(
        200,
        "application/json",
        "{\"choices\": [oops",
    )]);
    let err = client(&server).chat("m").chat(&request()).unwrap_err();
    assert!(
        matches!(err.kind, ProviderErrorKind::Malformed { .. }),
        "{err}"
    );
    assert!(
        err.to_string().contains("expected a JSON chat completion"),
        "{err}"
    );
    assert!(
        std::error::Error::source(&err).is_some(),
        "keeps the parser error"
    );
    // JSON, but not a completion.
    let server = TestServer::scripted(vec![Reply::json(200, &json!({"result": "ok"}))]);
    let err = client(&server).chat("m").chat(&request()).unwrap_err();
    assert!(
        err.to_string().contains("choices[0].message.content"),
        "{err}"
    );
    // A completion whose content is prose twice (first answer and repair).
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("m", "I cannot do that."),
    )]);
    let err = client(&server).chat("m").chat(&request()).unwrap_err();
    assert!(err.to_string().contains("after one repair round"), "{err}");
}

#[test]
fn http_429_waits_for_retry_after_then_succeeds() {
    let server = TestServer::scripted(vec![
        Reply::json(
            429,
            &json!({"error": {"message": "Rate limit reached for gpt-4o"}}),
        )
        .header("Retry-After", "0.3"),
        Reply::json(200, &openai_completion("m", GOOD)),
    ]);
    let chat = client(&server).chat("m");
    let started = Instant::now();
    chat.chat(&request()).unwrap();
    assert!(
        started.elapsed() >= Duration::from_millis(300),
        "{:?}",
        started.elapsed()
    );
    let usage = chat.meter().snapshot();
    assert_eq!((usage.requests, usage.retries), (2, 1));
}

#[test]
fn retry_after_beyond_the_budget_gives_up_at_once() {
    let server = TestServer::scripted(vec![Reply::json(
        429,
        &json!({"error": {"message": "slow down"}}),
    )
    .header("Retry-After", "30")]);
    let mut c = config(&server);
    c.budget = Duration::from_secs(2);
    let started = Instant::now();
    let err = OpenAiClient::new(c)
        .unwrap()
        .chat("m")
        .chat(&ChatRequest::new(vec![Message::user("hi")]))
        .unwrap_err();
    assert!(started.elapsed() < Duration::from_secs(2));
    assert!(
        matches!(
            err.kind,
            ProviderErrorKind::BudgetExhausted { attempts: 1, .. }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("slow down"), "{err}");
    assert!(
        err.to_string()
            .contains("the server asked to wait 30 s before retrying (Retry-After)"),
        "{err}"
    );
    // A wait far past any budget is reported as asked, not cut to an hour.
    let server = TestServer::scripted(vec![
        Reply::json(429, &json!({"error": "busy"})).header("Retry-After", "100000")
    ]);
    let err = client(&server)
        .chat("m")
        .chat(&ChatRequest::new(vec![Message::user("hi")]))
        .unwrap_err();
    assert!(err.to_string().contains("wait 100000 s"), "{err}");
}

#[test]
fn persistent_500_is_retried_then_reported() {
    let server = TestServer::scripted(vec![Reply::json(
        500,
        &json!({"error": {"message": "CUDA out of memory"}}),
    )]);
    let chat = client(&server).chat("llama3");
    let err = chat
        .chat(&ChatRequest::new(vec![Message::user("hi")]))
        .unwrap_err();
    assert_eq!(server.requests().len(), 3, "max_attempts");
    assert!(matches!(
        err.kind,
        ProviderErrorKind::Status { status: 500, .. }
    ));
    assert_eq!(
        err.to_string(),
        format!(
            "{}/chat/completions (model `llama3`): HTTP 500: CUDA out of memory",
            server.base_url
        )
    );
    assert_eq!(chat.meter().snapshot().retries, 2);
}

#[test]
fn unauthorised_is_not_retried_and_does_not_echo_the_key() {
    let server = TestServer::scripted(vec![Reply::json(
        401,
        &json!({"error": {"message": "Incorrect API key provided"}}),
    )]);
    let err = client(&server).chat("m").chat(&request()).unwrap_err();
    assert_eq!(server.requests().len(), 1);
    assert!(err.to_string().contains("HTTP 401"), "{err}");
    assert_no_key(&format!("{err} {err:?}"));
}

#[test]
fn a_server_echoing_the_key_has_it_masked_before_the_message_is_shortened() {
    let echo = format!("Incorrect API key provided: {KEY}. {}", "x".repeat(400));
    let server = TestServer::scripted(vec![Reply::json(401, &json!({"error": {"message": echo}}))]);
    let err = client(&server).chat("m").chat(&request()).unwrap_err();
    let text = err.to_string();
    assert!(text.contains("Incorrect API key provided: ***"), "{text}");
    assert_no_key(&format!("{err} {err:?}"));
    // No prefix of the key survives either (a shortened message could cut it).
    assert!(!text.contains(&KEY[..8]), "{text}");
}

#[test]
fn a_reply_slower_than_the_timeout_is_a_timeout() {
    let server = TestServer::scripted(vec![
        Reply::json(200, &openai_completion("m", GOOD)).delayed(Duration::from_millis(1500))
    ]);
    let mut c = config(&server);
    c.timeout = Duration::from_millis(300);
    c.max_attempts = 1;
    let started = Instant::now();
    let err = OpenAiClient::new(c)
        .unwrap()
        .chat("slow")
        .chat(&request())
        .unwrap_err();
    assert!(
        started.elapsed() < Duration::from_millis(1400),
        "{:?}",
        started.elapsed()
    );
    assert!(
        matches!(err.kind, ProviderErrorKind::Timeout { .. }),
        "{err}"
    );
    assert!(
        err.to_string()
            .contains("(model `slow`): no answer within 0.3 s"),
        "{err}"
    );
}

#[test]
fn connection_refused_names_the_endpoint() {
    let port = {
        let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        l.local_addr().unwrap().port()
    };
    let mut c = ClientConfig::new(format!("http://127.0.0.1:{port}/v1"));
    c.api_key = Some(ApiKey::new(KEY));
    c.max_attempts = 2;
    c.backoff = Duration::from_millis(10);
    let chat = OpenAiClient::new(c).unwrap().chat("gpt-4o");
    let err = chat.chat(&request()).unwrap_err();
    assert!(
        matches!(err.kind, ProviderErrorKind::Unreachable { .. }),
        "{err}"
    );
    let text = err.to_string();
    assert!(text.starts_with(&format!("http://127.0.0.1:{port}/v1/chat/completions (model `gpt-4o`): the server is unreachable")), "{text}");
    assert!(std::error::Error::source(&err).is_some());
    assert_no_key(&format!("{text} {err:?}"));
    assert_eq!(chat.meter().snapshot().requests, 2);
}

#[test]
fn image_generation_accepts_b64_json_and_urls() {
    let red = png(8, 8, [255, 0, 0]);
    let blue = png(8, 8, [0, 0, 255]);
    let b64 = ImageData::from_bytes(red.clone(), "t").unwrap().to_base64();
    let blue_served = blue.clone();
    let server = TestServer::start(move |_, r| match r.path.as_str() {
        "/v1/images/generations" => {
            let body = r.json();
            if body["model"] == "gpt-image-1" {
                Reply::json(
                    200,
                    &json!({"created": 1, "data": [{"b64_json": b64}],
                    "usage": {"input_tokens": 10, "output_tokens": 100, "total_tokens": 110}}),
                )
            } else {
                // LocalAI answers a relative URL.
                Reply::json(
                    200,
                    &json!({"created": 1, "data": [{"url": "/generated-images/b64.png", "revised_prompt": "a blue room"}]}),
                )
            }
        }
        "/generated-images/b64.png" => Reply::raw(200, "image/png", blue_served.clone()),
        _ => Reply::json(404, &json!({"error": "not found"})),
    });
    let c = client(&server);
    let req = ImageRequest {
        prompt: "an empty pharmacy".into(),
        size: [1024, 1024],
        seed: Some(7),
    };
    let img = c.images("gpt-image-1").generate(&req).unwrap();
    assert_eq!(img.image.bytes, red);
    let sent = server.requests()[0].json();
    assert_eq!(sent["size"], "1024x1024");
    assert!(
        sent.get("response_format").is_none(),
        "GPT image models reject response_format"
    );
    let img = c.images("stablediffusion").generate(&req).unwrap();
    assert_eq!(img.image.bytes, blue);
    assert_eq!(img.revised_prompt.as_deref(), Some("a blue room"));
    assert_eq!(server.requests()[2].path, "/generated-images/b64.png");
}

#[test]
fn image_edit_is_multipart_and_dalle_asks_for_base64() {
    let source = png(4, 4, [10, 200, 10]);
    let result = png(4, 4, [1, 2, 3]);
    let b64 = ImageData::from_bytes(result.clone(), "t")
        .unwrap()
        .to_base64();
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &json!({"created": 1, "data": [{"b64_json": b64}]}),
    )]);
    let edit = ImageEditRequest {
        prompt: "add shelves".into(),
        image: ImageData::from_bytes(source.clone(), "render").unwrap(),
        mask: Some(ImageData::from_bytes(png(4, 4, [0, 0, 0]), "mask").unwrap()),
        size: [512, 512],
        seed: None,
    };
    let out = client(&server).images("dall-e-2").edit(&edit).unwrap();
    assert_eq!(out.image.bytes, result);
    let r = &server.requests()[0];
    assert_eq!(r.path, "/v1/images/edits");
    assert!(r
        .header("content-type")
        .unwrap()
        .starts_with("multipart/form-data; boundary="));
    let body = String::from_utf8_lossy(&r.body);
    for needle in [
        "name=\"model\"\r\n\r\ndall-e-2",
        "name=\"prompt\"\r\n\r\nadd shelves",
        "name=\"size\"\r\n\r\n512x512",
        "name=\"response_format\"\r\n\r\nb64_json",
        "name=\"image\"; filename=\"image.png\"",
        "name=\"mask\"; filename=\"mask.png\"",
        "Content-Type: image/png",
    ] {
        assert!(body.contains(needle), "missing {needle:?}");
    }
    assert!(
        r.body.windows(source.len()).any(|w| w == source.as_slice()),
        "the image bytes are sent"
    );
}

#[test]
fn image_answer_without_image_is_malformed() {
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &json!({"data": [{"revised_prompt": "x"}]}),
    )]);
    let req = ImageRequest {
        prompt: "x".into(),
        size: [64, 64],
        seed: None,
    };
    let err = client(&server).images("sd").generate(&req).unwrap_err();
    assert!(
        err.to_string()
            .contains("expected `data[0].b64_json` or `data[0].url`"),
        "{err}"
    );
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &json!({"data": [{"b64_json": "R0lGODlh"}]}),
    )]);
    let err = client(&server).images("sd").generate(&req).unwrap_err();
    assert!(err.to_string().contains("expected PNG or JPEG"), "{err}");
}

#[test]
fn embeddings_in_index_order_and_as_a_trait_object() {
    let server = TestServer::start(|_, r| {
        let body = r.json();
        let n = body["input"].as_array().unwrap().len();
        // Answer out of order, as some servers do.
        let data: Vec<Value> = (0..n)
            .rev()
            .map(|i| json!({"object": "embedding", "index": i, "embedding": [i as f32, 1.0, 0.5]}))
            .collect();
        Reply::json(
            200,
            &json!({"object": "list", "data": data, "model": "nomic-embed-text",
                                 "usage": {"prompt_tokens": 6, "total_tokens": 6}}),
        )
    });
    let embedder = client(&server).embedder("nomic-embed-text");
    let v = TextEmbedder::embed(&embedder, &["sofa", "couch", "lamp"]).unwrap();
    assert_eq!(
        v,
        vec![
            vec![0.0, 1.0, 0.5],
            vec![1.0, 1.0, 0.5],
            vec![2.0, 1.0, 0.5]
        ]
    );
    assert_eq!(
        server.requests()[0].json()["input"],
        json!(["sofa", "couch", "lamp"])
    );
    let as_dyn: &dyn TextEmbedder = &embedder;
    assert_eq!(as_dyn.embed(&["x"]).unwrap(), vec![vec![0.0, 1.0, 0.5]]);
    assert_eq!(embedder.meter().snapshot().prompt_tokens, 12);

    let server = TestServer::scripted(vec![Reply::json(
        200,
        &json!({"data": [{"index": 0, "embedding": [1.0]}]}),
    )]);
    let err = TextEmbedder::embed(&client(&server).embedder("e"), &["a", "b"]).unwrap_err();
    assert!(
        err.to_string().contains("expected 2 embeddings, found 1"),
        "{err}"
    );
}

#[test]
fn cached_client_replays_offline_byte_for_byte() {
    let dir = tempfile::tempdir().unwrap();
    let recorded = {
        let server =
            TestServer::scripted(vec![Reply::json(200, &openai_completion("gpt-4o", GOOD))]);
        let cached = Cached::new(
            client(&server).chat("gpt-4o"),
            ResponseCache::open(dir.path(), CacheMode::ReadWrite).unwrap(),
        );
        let first = cached.chat(&request()).unwrap();
        assert_eq!(cached.chat(&request()).unwrap(), first);
        assert_eq!(server.requests().len(), 1, "the second call is a cache hit");
        first
    };
    // The server is gone; replay needs only the cache.
    let files: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(files.len(), 1);
    let cache_bytes = std::fs::read(files[0].as_ref().unwrap().path()).unwrap();
    assert_no_key(&String::from_utf8_lossy(&cache_bytes));
    let offline = OpenAiClient::new(ClientConfig::new("http://127.0.0.1:9/v1")).unwrap();
    let replay = Cached::new(
        offline.chat("gpt-4o"),
        ResponseCache::open(dir.path(), CacheMode::ReplayOnly).unwrap(),
    );
    let again = replay.chat(&request()).unwrap();
    assert_eq!(again, recorded);
    assert_eq!(
        serde_json::to_vec(&again).unwrap(),
        serde_json::to_vec(&recorded).unwrap()
    );
    let mut other = request();
    other.messages[1] = Message::user("List the objects of a hair salon.");
    let err = replay.chat(&other).unwrap_err();
    assert!(
        matches!(err.kind, ProviderErrorKind::CacheMiss { .. }),
        "{err}"
    );
}

#[test]
fn a_transient_5xx_under_json_schema_is_retried_not_taken_as_a_format_rejection() {
    let server = TestServer::scripted(vec![
        Reply::json(503, &json!({"error": {"message": "model is loading"}})),
        Reply::json(200, &vllm_completion("m", GOOD)),
    ]);
    let chat = client(&server).chat("m");
    let answer = chat.chat(&request()).unwrap();
    assert!(answer.notes.is_empty(), "{:?}", answer.notes);
    assert_eq!(chat.first_format(), OutputFormat::JsonSchema);
    let requests = server.requests();
    assert_eq!(requests.len(), 2);
    assert_eq!(requests[1].json()["response_format"]["type"], "json_schema");
    assert_eq!(chat.meter().snapshot().retries, 1);
}

#[test]
fn one_client_serves_several_threads_at_once() {
    let server = TestServer::scripted(vec![
        Reply::json(200, &openai_completion("m", GOOD)).delayed(Duration::from_millis(200))
    ]);
    let chat = std::sync::Arc::new(client(&server).chat("m"));
    let started = Instant::now();
    let handles: Vec<_> = (0..4)
        .map(|_| {
            let chat = std::sync::Arc::clone(&chat);
            std::thread::spawn(move || chat.chat(&request()).map(|a| a.json))
        })
        .collect();
    for h in handles {
        assert_eq!(h.join().unwrap().unwrap().unwrap()["anchor"], "counter");
    }
    assert_eq!(chat.meter().snapshot().requests, 4);
    // The calls overlap rather than queue behind one another.
    assert!(
        started.elapsed() < Duration::from_millis(750),
        "{:?}",
        started.elapsed()
    );
}

#[test]
fn a_key_echoed_in_a_malformed_body_or_in_model_text_is_masked() {
    // An HTML error page holding the key, with a 200 status.
    let page = format!("<html><body>Bad gateway for Bearer {KEY}</body></html>");
    let server = TestServer::scripted(vec![Reply::raw(200, "text/html", page)]);
    let err = client(&server).chat("m").chat(&request()).unwrap_err();
    assert!(err.to_string().contains("Bearer ***"), "{err}");
    assert_no_key(&format!("{err} {err:?}"));
    // A 502 HTML page holding the key: retried (the warnings carry the message) then reported.
    let server = TestServer::scripted(vec![Reply::raw(502, "text/html", format!("<p>{KEY}</p>"))]);
    let err = client(&server).chat("m").chat(&request()).unwrap_err();
    assert_no_key(&format!("{err} {err:?}"));
    // Model text holding the key, raw and spelled with JSON escapes.
    let escaped: String = KEY
        .chars()
        .map(|c| format!("\\u{:04x}", c as u32))
        .collect();
    for content in [format!("the key is {KEY}"), format!("the key is {escaped}")] {
        let body = openai_completion("m", "x")
            .to_string()
            .replace("\"content\":\"x\"", &format!("\"content\":\"{content}\""));
        let server = TestServer::scripted(vec![Reply::raw(200, "application/json", body)]);
        let answer = client(&server)
            .chat("m")
            .chat(&ChatRequest::new(vec![Message::user("hi")]))
            .unwrap();
        assert_eq!(answer.text, "the key is ***");
    }
    // A structured answer holding the key: masked in the text and the parsed value.
    let leaky = format!(
        r#"{{"anchor":"{KEY}","objects":[{{"category":"a","count":1}},{{"category":"b","count":2}}]}}"#
    );
    let server = TestServer::scripted(vec![Reply::json(200, &openai_completion("m", &leaky))]);
    let answer = client(&server).chat("m").chat(&request()).unwrap();
    assert_no_key(&format!("{answer:?}"));
    assert_eq!(answer.json.unwrap()["anchor"], "***");
}

#[test]
fn an_answer_past_the_size_limit_is_refused_while_reading() {
    let server = TestServer::scripted(vec![Reply::json(
        200,
        &openai_completion("m", &"y".repeat(5000)),
    )]);
    let mut c = config(&server);
    c.max_response_bytes = 1000;
    let err = OpenAiClient::new(c)
        .unwrap()
        .chat("m")
        .chat(&ChatRequest::new(vec![Message::user("hi")]))
        .unwrap_err();
    assert!(
        matches!(err.kind, ProviderErrorKind::Malformed { .. }),
        "{err}"
    );
    assert!(
        err.to_string()
            .contains("larger than the limit of 1000 bytes"),
        "{err}"
    );
    assert_eq!(server.requests().len(), 1, "not retried");
    assert_eq!(
        ClientConfig::new("http://x").max_response_bytes,
        scenethesis_openai::MAX_RESPONSE_BYTES
    );
}

#[test]
fn a_lenient_request_gets_a_cut_off_answer_back_without_a_repair_round() {
    let mut cut = openai_completion("m", &GOOD[..40]);
    cut["choices"][0]["finish_reason"] = json!("length");
    let server = TestServer::scripted(vec![Reply::json(200, &cut)]);
    let mut lenient = request();
    lenient.lenient = true;
    lenient.max_tokens = Some(64);
    let answer = client(&server).chat("m").chat(&lenient).unwrap();
    assert_eq!(
        server.requests().len(),
        1,
        "no repair round for a cut-off answer"
    );
    assert_eq!(server.requests()[0].json()["max_tokens"], 64);
    assert_eq!(answer.json, None);
    assert_eq!(answer.text, &GOOD[..40]);
    assert!(
        answer
            .notes
            .iter()
            .any(|n| n.contains("cut off at max_tokens (64)")),
        "{:?}",
        answer.notes
    );
    // Schema-violating after the repair round: handed back with the violation noted.
    let bad = r#"{"anchor":"counter","objects":[]}"#;
    let server = TestServer::scripted(vec![Reply::json(200, &openai_completion("m", bad))]);
    let answer = client(&server).chat("m").chat(&lenient).unwrap();
    assert_eq!(server.requests().len(), 2, "one repair round");
    assert_eq!(
        answer.json,
        Some(serde_json::from_str::<Value>(bad).unwrap())
    );
    assert!(
        answer
            .notes
            .iter()
            .any(|n| n.contains("after one repair round")),
        "{:?}",
        answer.notes
    );
    // The same answer to a strict request is still an error.
    let err = client(&server).chat("m").chat(&request()).unwrap_err();
    assert!(
        matches!(err.kind, ProviderErrorKind::Schema { .. }),
        "{err}"
    );
}

#[test]
fn a_config_file_is_read_with_a_size_limit() {
    let missing = std::path::Path::new("/dev/zero");
    let err =
        ClientConfig::resolve_with(&Overrides::default(), &|_| None, Some(missing)).unwrap_err();
    let text = format!("{err} {:?}", std::error::Error::source(&err));
    assert!(
        text.contains("/dev/zero") && text.contains("device"),
        "{text}"
    );
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.toml");
    std::fs::write(
        &big,
        vec![b'#'; scenethesis_openai::MAX_CONFIG_BYTES as usize + 1],
    )
    .unwrap();
    let err = ClientConfig::resolve_with(&Overrides::default(), &|_| None, Some(&big)).unwrap_err();
    let text = format!("{err} {:?}", std::error::Error::source(&err));
    assert!(text.contains("larger than the limit"), "{text}");
}

#[test]
fn a_key_echoed_reshaped_is_masked() {
    // Split by newlines and hyphens, re-cased, or in part: an error message and model text.
    let reshaped = [
        KEY.replace('-', "\n-\n"),
        KEY.to_lowercase(),
        KEY.chars().map(String::from).collect::<Vec<_>>().join(" "),
        KEY[5..].to_string(),
    ];
    for echo in &reshaped {
        let server = TestServer::scripted(vec![Reply::json(
            401,
            &json!({"error": {"message": format!("no such key: {echo}.")}}),
        )]);
        let err = client(&server).chat("m").chat(&request()).unwrap_err();
        let text = format!("{err} {err:?}");
        assert!(text.contains("no such key: ***."), "{text}");
        assert!(!text.contains("LEAK"), "{text}");
        let server = TestServer::scripted(vec![Reply::json(
            200,
            &openai_completion("m", &format!("it was {echo}")),
        )]);
        let answer = client(&server)
            .chat("m")
            .chat(&ChatRequest::new(vec![Message::user("hi")]))
            .unwrap();
        assert_eq!(answer.text, "it was ***", "{echo:?}");
    }
}
