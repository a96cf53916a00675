//! `scenethesis generate --planner llm` against a chat server on 127.0.0.1 that the tests start
//! and stop: a model's own plan for "a pharmacy", `report.json` naming the
//! provider and model (never the key), a byte-identical replay from `--llm-cache` with the
//! server gone, and provider failures (HTTP 500, garbage, a reply slower than the timeout,
//! connection refused) that give one error naming endpoint and model and write no folder.

use std::path::Path;
use std::process::{Command, Output};
use std::time::Duration;

use scenethesis_openai::testing::{Reply, TestServer};
use serde_json::{json, Value};

mod common;
use common::text;

const KEY: &str = "sk-test-4f9c1e0b7d2a-never-print-me";

/// What the server answers: status, content type, body, delay.
type Answer = (u16, &'static str, Vec<u8>, Duration);

/// The openai crate's loopback test server, answering every request with the same reply.
struct Server(TestServer);

impl Server {
    fn start((status, content_type, body, delay): Answer) -> Self {
        let reply = Reply::raw(status, content_type, body).delayed(delay);
        Self(TestServer::start(move |_, _| reply.clone()))
    }

    fn requests(&self) -> usize {
        self.0.requests().len()
    }
}

impl std::ops::Deref for Server {
    type Target = TestServer;

    fn deref(&self) -> &TestServer {
        &self.0
    }
}

/// A model's plan for "a pharmacy" (its own, not the offline thesaurus reading), shared with the
/// language crate's tests: `fixtures/llm/pharmacy_plan.json`.
fn pharmacy_plan() -> Value {
    serde_json::from_str(include_str!("../../../fixtures/llm/pharmacy_plan.json"))
        .expect("the pharmacy fixture is JSON")
}

/// A chat completion in OpenAI's shape holding `content`.
fn completion(content: &str) -> Vec<u8> {
    json!({
        "id": "chatcmpl-AbC123", "object": "chat.completion", "created": 1764100000,
        "model": "pharmacist-7b",
        "choices": [{"index": 0, "finish_reason": "stop",
                     "message": {"role": "assistant", "content": content, "refusal": null}}],
        "usage": {"prompt_tokens": 900, "completion_tokens": 700, "total_tokens": 1600}
    })
    .to_string()
    .into_bytes()
}

fn scenethesis(args: &[&str]) -> Output {
    common::scenethesis_with_key(Some(KEY), args)
}

/// A config file making failures fast: one attempt, short timeout.
fn fast_config(dir: &Path) -> String {
    let path = dir.join("llm.toml");
    std::fs::write(
        &path,
        "max_attempts = 1\ntimeout_secs = 1.0\nbudget_secs = 5.0\nbackoff_ms = 10\n",
    )
    .unwrap();
    path.to_string_lossy().into_owned()
}

fn generate_llm(base_url: &str, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "generate",
        "a pharmacy",
        "--planner",
        "llm",
        "--base-url",
        base_url,
        "--llm-model",
        "pharmacist-7b",
        "--no-preview",
        "--max-replans",
        "1",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    scenethesis(&args)
}

fn files_contain(dir: &Path, needle: &str) -> bool {
    std::fs::read_dir(dir).unwrap().flatten().any(|e| {
        let p = e.path();
        if p.is_dir() {
            files_contain(&p, needle)
        } else {
            std::fs::read(&p)
                .map(|b| String::from_utf8_lossy(&b).contains(needle))
                .unwrap_or(false)
        }
    })
}

#[test]
fn an_llm_plans_a_pharmacy_and_the_cache_replays_it_without_the_server() {
    let tmp = tempfile::tempdir().unwrap();
    let cache = tmp.path().join("cache");
    let cache_arg = cache.to_str().unwrap().to_owned();
    let first = tmp.path().join("first");
    let server = Server::start((
        200,
        "application/json",
        completion(&pharmacy_plan().to_string()),
        Duration::ZERO,
    ));
    let out = generate_llm(&server.base_url, &first, &["--llm-cache", &cache_arg]);
    let log = text(&out);
    assert!(out.status.success(), "{log}");
    assert!(server.requests() >= 1);
    assert!(!log.contains(KEY), "the key leaked into the output: {log}");

    let report: Value =
        serde_json::from_slice(&std::fs::read(first.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["scene_type"], "pharmacy", "{report}");
    assert_eq!(report["accepted"], true, "{}", report["verdict"]);
    let providers = report["providers"].as_array().expect("providers recorded");
    assert_eq!(providers.len(), 1, "{report}");
    let p = &providers[0];
    assert_eq!(p["model"], "pharmacist-7b");
    assert_eq!(p["provider"], server.base_url.as_str());
    assert_eq!(p["requests"], server.requests() as u64);
    assert_eq!(p["cache_hits"], 0);
    assert_eq!(p["prompt_tokens"], 900 * server.requests() as u64);
    assert!(
        !files_contain(&first, KEY),
        "the key is in the output folder"
    );
    assert!(
        !files_contain(&cache, KEY),
        "the key is in the response cache"
    );
    let scene = std::fs::read(first.join("scene.json")).unwrap();
    let served = server.requests();
    drop(server);

    // The server is gone: replay from the cache, byte for byte.
    let dead = {
        let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        format!("http://{}/v1", l.local_addr().unwrap())
    };
    let second = tmp.path().join("second");
    let out = generate_llm(&dead, &second, &["--llm-cache", &cache_arg, "--llm-replay"]);
    assert!(out.status.success(), "{}", text(&out));
    assert_eq!(std::fs::read(second.join("scene.json")).unwrap(), scene);
    let report: Value =
        serde_json::from_slice(&std::fs::read(second.join("report.json")).unwrap()).unwrap();
    let p = &report["providers"][0];
    assert_eq!(p["requests"], 0, "{report}");
    assert_eq!(p["cache_hits"], served as u64, "{report}");
}

#[test]
fn each_batch_job_reports_its_own_use_of_the_model() {
    let tmp = tempfile::tempdir().unwrap();
    let server = Server::start((
        200,
        "application/json",
        completion(&pharmacy_plan().to_string()),
        Duration::ZERO,
    ));
    let prompts = tmp.path().join("prompts.txt");
    std::fs::write(&prompts, "a pharmacy\n").unwrap();
    let out_dir = tmp.path().join("batch");
    let out = scenethesis(&[
        "batch",
        prompts.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--seeds",
        "2",
        "--jobs",
        "2",
        "--planner",
        "llm",
        "--base-url",
        &server.base_url,
        "--llm-model",
        "pharmacist-7b",
        "--no-preview",
        "--max-replans",
        "1",
    ]);
    assert!(out.status.success(), "{}", text(&out));
    let mut reports = Vec::new();
    for entry in std::fs::read_dir(&out_dir).unwrap().flatten() {
        let path = entry.path().join("report.json");
        if path.is_file() {
            reports.push(serde_json::from_slice::<Value>(&std::fs::read(path).unwrap()).unwrap());
        }
    }
    assert_eq!(reports.len(), 2, "two jobs, two folders");
    let mut total = 0;
    for report in &reports {
        let providers = report["providers"].as_array().expect("providers recorded");
        assert_eq!(providers.len(), 1, "{report}");
        assert_eq!(providers[0]["model"], "pharmacist-7b");
        let requests = providers[0]["requests"].as_u64().unwrap();
        assert!(requests >= 1, "each job planned with the model: {report}");
        assert_eq!(providers[0]["prompt_tokens"], 900 * requests, "{report}");
        total += requests;
    }
    // The jobs ran in parallel on one shared client; each counted only its own requests.
    assert_eq!(total, server.requests() as u64);
}

#[test]
fn the_offline_default_reads_no_provider_configuration_and_reports_none() {
    let tmp = tempfile::tempdir().unwrap();
    let out_dir = tmp.path().join("garage");
    // A broken base URL in the environment does not matter offline.
    let out = Command::new(env!("CARGO_BIN_EXE_scenethesis"))
        .env("OPENAI_BASE_URL", "not a url")
        .env("OPENAI_API_KEY", KEY)
        .args([
            "generate",
            "a garage",
            "--no-preview",
            "--out",
            out_dir.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", text(&out));
    let report: Value =
        serde_json::from_slice(&std::fs::read(out_dir.join("report.json")).unwrap()).unwrap();
    assert!(report.get("providers").is_none(), "{report}");
}

/// A failing provider: non-zero exit, one error naming endpoint and model, no folder.
fn assert_fails_cleanly(base_url: &str, needle: &str) {
    let tmp = tempfile::tempdir().unwrap();
    let out_dir = tmp.path().join("pharmacy");
    let config = fast_config(tmp.path());
    let out = generate_llm(base_url, &out_dir, &["--llm-config", &config]);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "{stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert_eq!(
        stderr.matches("error: ").count(),
        1,
        "one error, not several: {stderr}"
    );
    assert!(
        stderr.contains(&format!("{base_url}/chat/completions")),
        "the endpoint is named: {stderr}"
    );
    assert!(
        stderr.contains("pharmacist-7b"),
        "the model is named: {stderr}"
    );
    assert!(stderr.contains(needle), "{stderr}");
    assert!(!stderr.contains(KEY), "the key leaked: {stderr}");
    assert!(!out_dir.exists(), "no output folder on a provider failure");
}

#[test]
fn provider_failures_give_one_clear_error_and_no_output() {
    let server = Server::start((
        500,
        "application/json",
        br#"{"error": {"message": "CUDA out of memory"}}"#.to_vec(),
        Duration::ZERO,
    ));
    assert_fails_cleanly(&server.base_url, "HTTP 500");
    drop(server);

    let server = Server::start((
        200,
        "text/html",
        b"<html><body>502 Bad Gateway</body></html>".to_vec(),
        Duration::ZERO,
    ));
    assert_fails_cleanly(&server.base_url, "malformed");
    drop(server);

    // An answer breaking the plan schema (answer and repair round) is salvaged: the plan is
    // completed from offline knowledge and the run gives a scene, saying so (issue 32, item 20).
    let server = Server::start((
        200,
        "application/json",
        completion(r#"{"objects": "a counter and some shelves"}"#),
        Duration::ZERO,
    ));
    let tmp = tempfile::tempdir().unwrap();
    let out_dir = tmp.path().join("pharmacy");
    let config = fast_config(tmp.path());
    let out = generate_llm(&server.base_url, &out_dir, &["--llm-config", &config]);
    assert!(out.status.success(), "{}", text(&out));
    let report = std::fs::read_to_string(out_dir.join("report.json")).unwrap();
    assert!(report.contains("violates the JSON schema"), "{report}");
    assert!(
        report.contains("completed from offline knowledge"),
        "{report}"
    );
    assert!(!report.contains(KEY), "the key leaked: {report}");
    drop(server);

    let server = Server::start((
        200,
        "application/json",
        completion(&pharmacy_plan().to_string()),
        Duration::from_secs(3),
    ));
    assert_fails_cleanly(&server.base_url, "no answer within");
    drop(server);

    let refused = {
        let l = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
        format!("http://{}/v1", l.local_addr().unwrap())
    };
    assert_fails_cleanly(&refused, "unreachable");
}

#[test]
fn an_llm_planner_without_a_model_name_says_how_to_set_one() {
    let tmp = tempfile::tempdir().unwrap();
    let out_dir = tmp.path().join("x");
    let out = scenethesis(&[
        "generate",
        "a pharmacy",
        "--planner",
        "llm",
        "--base-url",
        "http://127.0.0.1:9/v1",
        "--no-preview",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success());
    assert!(stderr.contains("--llm-model"), "{stderr}");
    assert!(stderr.contains("SCENETHESIS_LLM_MODEL"), "{stderr}");
    assert!(!out_dir.exists());
}

#[test]
fn a_vlm_judge_reviews_rendered_previews_and_the_review_is_reported() {
    let review = json!({"category_accuracy": 0.92, "orientation_alignment": 0.81,
                        "spatial_coherence": 0.88, "objects": [],
                        "summary": "a plausible garage"});
    let server = Server::start((
        200,
        "application/json",
        completion(&review.to_string()),
        Duration::ZERO,
    ));
    let tmp = tempfile::tempdir().unwrap();
    let out_dir = tmp.path().join("garage");
    let out = scenethesis(&[
        "generate",
        "a garage",
        "--judge",
        "vlm",
        "--vlm-model",
        "eye-1",
        "--base-url",
        &server.base_url,
        "--no-preview",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    let log = text(&out);
    if log.contains("needs a renderer") {
        eprintln!("skipped: no renderer on this machine: {log}");
        return;
    }
    assert!(out.status.success(), "{log}");
    assert!(server.requests() >= 1);
    let report: Value =
        serde_json::from_slice(&std::fs::read(out_dir.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["judge"], "geometric+vlm:openai-compatible/eye-1");
    let r = &report["verdict"]["review"];
    assert_eq!(r["spatial_coherence"], 0.88, "{report}");
    assert_eq!(r["accepted"], true);
    assert!(!r["views"].as_array().unwrap().is_empty());
    assert_eq!(report["providers"][0]["model"], "eye-1");
    assert!(!files_contain(&out_dir, KEY));
}
