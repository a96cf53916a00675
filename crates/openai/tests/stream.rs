//! Streamed chat answers against real HTTP on 127.0.0.1: long answers are asked for as a stream
//! and assembled with progress reported; a server that ignores `stream` still works; a stream
//! that stalls or is cut off says how much had arrived (and a lenient request keeps that part);
//! an echoed key is masked however it is reshaped; the response cache is unchanged by streaming.

mod support;

use std::cell::RefCell;
use std::rc::Rc;
use std::time::Duration;

use scenethesis_models::{
    with_answer_listener, AnswerProgress, CacheMode, Cached, ChatModel, ChatRequest, JsonSchema,
    Message, ProviderErrorKind, ResponseCache,
};
use scenethesis_openai::{ApiKey, ClientConfig, OpenAiChat, OpenAiClient};
use serde_json::json;
use support::{openai_completion, openai_stream, Reply, TestServer};

const KEY: &str = "sk-proj-Stream9Secret7Key5Abc";

const ANSWER: &str = r#"{"anchor":"counter","objects":[{"category":"counter","count":1},{"category":"shelf","count":6},{"category":"chair","count":2}]}"#;

fn config(server: &TestServer) -> ClientConfig {
    let mut c = ClientConfig::new(&server.base_url);
    c.api_key = Some(ApiKey::new(KEY));
    c.timeout = Duration::from_secs(5);
    c.backoff = Duration::from_millis(20);
    c.max_attempts = 1;
    c
}

fn chat_with(c: ClientConfig) -> OpenAiChat {
    OpenAiClient::new(c).unwrap().chat("m")
}

fn schema() -> JsonSchema {
    JsonSchema::new(
        "room",
        json!({"type": "object", "required": ["anchor", "objects"], "properties": {
            "anchor": {"type": "string"},
            "objects": {"type": "array", "minItems": 2, "items": {"type": "object",
                "required": ["category", "count"], "properties": {
                    "category": {"type": "string"}, "count": {"type": "integer"}}}}}}),
    )
    .unwrap()
}

fn request(lenient: bool) -> ChatRequest {
    let mut r = ChatRequest::structured(vec![Message::user("List a pharmacy.")], schema());
    r.max_tokens = Some(2000);
    r.lenient = lenient;
    r
}

/// `text` in pieces of `n` characters.
fn pieces(text: &str, n: usize) -> Vec<String> {
    let chars: Vec<char> = text.chars().collect();
    chars.chunks(n).map(|c| c.iter().collect()).collect()
}

fn stream_of(text: &str, n: usize) -> Vec<String> {
    let parts = pieces(text, n);
    let refs: Vec<&str> = parts.iter().map(String::as_str).collect();
    openai_stream("m-served", &refs)
}

#[test]
fn a_long_answer_streams_with_progress_and_assembles() {
    let server = TestServer::scripted(vec![Reply::events(
        stream_of(ANSWER, 7),
        Duration::from_millis(2),
    )]);
    let heard: Rc<RefCell<Vec<AnswerProgress>>> = Rc::default();
    let sink = Rc::clone(&heard);
    let chat = chat_with(config(&server));
    let answer = with_answer_listener(
        Some(Box::new(move |p: &AnswerProgress| {
            sink.borrow_mut().push(*p)
        })),
        || chat.chat(&request(false)),
    )
    .unwrap();
    assert_eq!(answer.text, ANSWER);
    assert_eq!(answer.json.unwrap()["objects"][2]["category"], "chair");
    assert_eq!(answer.model, "m-served");
    let n = pieces(ANSWER, 7).len() as u64;
    assert_eq!(
        (answer.usage.prompt_tokens, answer.usage.completion_tokens),
        (90, n)
    );
    assert!(answer.notes.is_empty(), "{:?}", answer.notes);
    let body = server.requests()[0].json();
    assert_eq!(body["stream"], true);
    assert_eq!(body["stream_options"]["include_usage"], true);
    // Progress grew piece by piece up to the whole answer.
    let heard = heard.borrow();
    assert!(heard.len() >= 3, "{heard:?}");
    assert!(heard.windows(2).all(|w| w[0].characters <= w[1].characters));
    assert_eq!(heard.last().unwrap().characters, ANSWER.len());
    assert_eq!(heard.last().unwrap().pieces as u64, n);
}

#[test]
fn short_requests_and_a_config_without_streaming_are_not_streamed() {
    let server = TestServer::scripted(vec![Reply::json(200, &openai_completion("m", ANSWER))]);
    let mut short = request(false);
    short.max_tokens = Some(100);
    chat_with(config(&server)).chat(&short).unwrap();
    let mut c = config(&server);
    c.stream = false;
    chat_with(c).chat(&request(false)).unwrap();
    for r in server.requests() {
        assert!(r.json().get("stream").is_none(), "{}", r.json());
    }
}

#[test]
fn a_server_that_ignores_stream_and_answers_whole_works() {
    let server = TestServer::scripted(vec![Reply::json(200, &openai_completion("m", ANSWER))]);
    let answer = chat_with(config(&server)).chat(&request(false)).unwrap();
    assert_eq!(server.requests()[0].json()["stream"], true);
    assert_eq!(answer.text, ANSWER);
    assert_eq!(answer.usage.prompt_tokens, 120);
}

/// A stream of ANSWER in pieces of 10 characters that stalls for 3 s before its 5th event
/// (after the role event and 3 pieces: 30 characters).
fn stalling() -> Reply {
    Reply::events(stream_of(ANSWER, 10), Duration::ZERO).stall_before(4, Duration::from_secs(3))
}

#[test]
fn a_stalled_stream_times_out_saying_how_much_had_arrived() {
    let server = TestServer::scripted(vec![stalling()]);
    let mut c = config(&server);
    c.timeout = Duration::from_millis(600);
    let err = chat_with(c).chat(&request(false)).unwrap_err();
    assert!(
        matches!(
            err.kind,
            ProviderErrorKind::Timeout {
                received: Some(30),
                ..
            }
        ),
        "{err}"
    );
    assert!(
        err.to_string()
            .contains("timed out after 0.6 s with 30 characters of the answer received"),
        "{err}"
    );
}

#[test]
fn a_lenient_request_keeps_what_arrived_before_a_stall() {
    let server = TestServer::scripted(vec![stalling()]);
    let mut c = config(&server);
    c.timeout = Duration::from_millis(600);
    c.max_attempts = 3;
    let answer = chat_with(c).chat(&request(true)).unwrap();
    assert_eq!(answer.text, &ANSWER[..30]);
    assert_eq!(
        server.requests().len(),
        1,
        "the partial answer is used, not retried"
    );
    let notes = answer.notes.join(" | ");
    assert!(
        notes.contains("timed out after 0.6 s with 30 characters of the answer received"),
        "{notes}"
    );
    assert!(
        notes.contains("the part received is not valid JSON"),
        "{notes}"
    );
}

#[test]
fn a_cut_off_stream_is_retried_then_reported_or_kept_when_lenient() {
    let cut = Reply::events(stream_of(ANSWER, 10), Duration::ZERO).cut_after(6);
    let server = TestServer::scripted(vec![cut.clone()]);
    let mut c = config(&server);
    c.max_attempts = 2;
    let err = chat_with(c.clone()).chat(&request(false)).unwrap_err();
    assert_eq!(server.requests().len(), 2, "a cut connection is transient");
    assert!(
        err.to_string()
            .contains("the connection closed after 50 characters of the answer"),
        "{err}"
    );
    let server = TestServer::scripted(vec![cut]);
    c.base_url = server.base_url.clone();
    let answer = chat_with(c).chat(&request(true)).unwrap();
    assert_eq!(server.requests().len(), 1);
    assert_eq!(answer.text, &ANSWER[..50]);
    assert!(
        answer.notes[0].contains("the connection closed after 50 characters"),
        "{:?}",
        answer.notes
    );
}

#[test]
fn a_stream_past_the_size_limit_is_refused_while_reading() {
    let server = TestServer::scripted(vec![Reply::events(
        stream_of(&"y".repeat(4000), 50),
        Duration::ZERO,
    )]);
    let mut c = config(&server);
    c.max_response_bytes = 2000;
    c.max_attempts = 3;
    let err = chat_with(c).chat(&request(true)).unwrap_err();
    assert!(
        err.to_string()
            .contains("larger than the limit of 2000 bytes"),
        "{err}"
    );
    assert_eq!(server.requests().len(), 1, "not retried");
}

#[test]
fn a_key_echoed_in_the_stream_is_masked_whole_split_or_reshaped() {
    let dashed = KEY.replace('-', "\n- ");
    let spaced = KEY.chars().map(String::from).collect::<Vec<_>>().join(" ");
    for echo in [
        KEY.to_string(),
        dashed,
        spaced,
        KEY.to_uppercase(),
        KEY[6..].to_string(),
    ] {
        let text = format!("the key is <{echo}>!");
        let server = TestServer::scripted(vec![Reply::events(stream_of(&text, 3), Duration::ZERO)]);
        let answer = chat_with(config(&server))
            .chat(&ChatRequest::new(vec![Message::user("hi")]))
            .unwrap();
        assert_eq!(answer.text, "the key is <***>!", "{echo:?}");
    }
    // An error message echoing the key in pieces is masked too.
    let echo = format!("bad key {}", KEY.replace('-', " - "));
    let server = TestServer::scripted(vec![Reply::json(401, &json!({"error": {"message": echo}}))]);
    let err = chat_with(config(&server))
        .chat(&request(false))
        .unwrap_err();
    let text = format!("{err} {err:?}");
    assert!(text.contains("bad key ***"), "{text}");
    assert!(!text.contains("Secret7"), "{text}");
}

#[test]
fn the_cache_records_the_assembled_answer_and_replays_it_without_streaming() {
    let dir = tempfile::tempdir().unwrap();
    let server = TestServer::scripted(vec![Reply::events(stream_of(ANSWER, 9), Duration::ZERO)]);
    let recording = Cached::new(
        chat_with(config(&server)),
        ResponseCache::open(dir.path(), CacheMode::ReadWrite).unwrap(),
    );
    let first = recording.chat(&request(false)).unwrap();
    let entries: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(entries.len(), 1);
    // The same request with streaming off has the same key: it replays the recorded answer.
    let mut c = config(&server);
    c.stream = false;
    let replay = Cached::new(
        chat_with(c),
        ResponseCache::open(dir.path(), CacheMode::ReplayOnly).unwrap(),
    );
    assert_eq!(replay.chat(&request(false)).unwrap(), first);
    assert_eq!(server.requests().len(), 1);
    assert_eq!(first.text, ANSWER);
}

#[test]
fn an_error_inside_the_stream_is_reported_with_the_key_masked() {
    let mut events = stream_of(ANSWER, 10);
    events.truncate(3);
    events.push(format!(
        "data: {}\n\n",
        json!({"error": {"message": format!("worker crashed (key {KEY})")}})
    ));
    let server = TestServer::scripted(vec![Reply::events(events, Duration::ZERO)]);
    let err = chat_with(config(&server))
        .chat(&request(false))
        .unwrap_err();
    let text = format!("{err} {err:?}");
    assert!(
        text.contains("the server reported an error after 20 characters of the answer: worker crashed (key ***)"),
        "{text}"
    );
    assert!(!text.contains("Secret7"), "{text}");
}
