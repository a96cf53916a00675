//! A tiny HTTP/1.1 server on 127.0.0.1 for tests of OpenAI-compatible clients (feature
//! `test-server`): each connection is answered by a handler in its own thread, every request is
//! recorded, and dropping the server stops it. It also builds answers in the shapes OpenAI,
//! vLLM, Ollama and llama.cpp's server give. This crate's tests, the language agents' tests and
//! the CLI's tests all use it, so there is one test server, not one per crate.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use serde_json::Value;

/// A request as the server received it.
#[derive(Debug, Clone)]
pub struct Recorded {
    /// The HTTP method.
    pub method: String,
    /// The request path, e.g. `/v1/chat/completions`.
    pub path: String,
    /// Header names and values, in order.
    pub headers: Vec<(String, String)>,
    /// The request body.
    pub body: Vec<u8>,
}

impl Recorded {
    /// The first header named `name` (case-insensitive).
    pub fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.as_str())
    }

    /// The body parsed as JSON (panics when it is not).
    pub fn json(&self) -> Value {
        serde_json::from_slice(&self.body).expect("request body is JSON")
    }
}

/// What the server answers.
#[derive(Debug, Clone)]
pub struct Reply {
    /// HTTP status code.
    pub status: u16,
    /// Extra headers.
    pub headers: Vec<(String, String)>,
    /// The body.
    pub body: Vec<u8>,
    /// How long to wait before answering.
    pub delay: Duration,
    /// When not empty, the body is sent in these parts instead (HTTP chunked encoding), each
    /// after its pause: a streamed answer.
    pub parts: Vec<(Duration, Vec<u8>)>,
    /// With `parts`: the connection is closed after the last part without ending the body, as
    /// a server that crashes mid-answer does.
    pub cut: bool,
}

impl Reply {
    /// A JSON answer with `status`.
    pub fn json(status: u16, body: &Value) -> Self {
        Self {
            status,
            headers: vec![("Content-Type".into(), "application/json".into())],
            body: body.to_string().into_bytes(),
            delay: Duration::ZERO,
            parts: Vec::new(),
            cut: false,
        }
    }

    /// Any body with its content type.
    pub fn raw(status: u16, content_type: &str, body: impl Into<Vec<u8>>) -> Self {
        Self {
            status,
            headers: vec![("Content-Type".into(), content_type.into())],
            body: body.into(),
            delay: Duration::ZERO,
            parts: Vec::new(),
            cut: false,
        }
    }

    /// Adds a header.
    pub fn header(mut self, name: &str, value: &str) -> Self {
        self.headers.push((name.into(), value.into()));
        self
    }

    /// Answers only after `delay` (to test timeouts).
    pub fn delayed(mut self, delay: Duration) -> Self {
        self.delay = delay;
        self
    }

    /// A `text/event-stream` answer sent event by event, `pause` before each.
    pub fn events(events: Vec<String>, pause: Duration) -> Self {
        Self {
            parts: events
                .into_iter()
                .map(|e| (pause, e.into_bytes()))
                .collect(),
            ..Self::raw(200, "text/event-stream", Vec::new())
        }
    }

    /// Waits `pause` before the part at `index` (to stall a stream mid-answer).
    pub fn stall_before(mut self, index: usize, pause: Duration) -> Self {
        if let Some(part) = self.parts.get_mut(index) {
            part.0 = pause;
        }
        self
    }

    /// Sends only the first `keep` parts, then closes the connection mid-body.
    pub fn cut_after(mut self, keep: usize) -> Self {
        self.parts.truncate(keep);
        self.cut = true;
        self
    }
}

type Handler = dyn Fn(usize, &Recorded) -> Reply + Send + Sync;

/// The running server.
pub struct TestServer {
    /// `http://127.0.0.1:PORT/v1`, the base URL to give a client.
    pub base_url: String,
    addr: std::net::SocketAddr,
    requests: Arc<Mutex<Vec<Recorded>>>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl TestServer {
    /// Starts a server whose handler gets the request's number (from 0) and the request.
    pub fn start(handler: impl Fn(usize, &Recorded) -> Reply + Send + Sync + 'static) -> Self {
        let listener = TcpListener::bind("127.0.0.1:0").expect("bind 127.0.0.1");
        let addr = listener.local_addr().unwrap();
        let requests = Arc::new(Mutex::new(Vec::new()));
        let stop = Arc::new(AtomicBool::new(false));
        let handler: Arc<Handler> = Arc::new(handler);
        let counter = Arc::new(AtomicUsize::new(0));
        let thread = {
            let requests = Arc::clone(&requests);
            let stop = Arc::clone(&stop);
            std::thread::spawn(move || {
                for stream in listener.incoming() {
                    if stop.load(Ordering::SeqCst) {
                        break;
                    }
                    let Ok(stream) = stream else { continue };
                    let handler = Arc::clone(&handler);
                    let requests = Arc::clone(&requests);
                    let counter = Arc::clone(&counter);
                    std::thread::spawn(move || serve(stream, &*handler, &requests, &counter));
                }
            })
        };
        Self {
            base_url: format!("http://{addr}/v1"),
            addr,
            requests,
            stop,
            thread: Some(thread),
        }
    }

    /// Starts a server answering the replies in order (the last one repeatedly).
    pub fn scripted(replies: Vec<Reply>) -> Self {
        Self::start(move |i, _| replies[i.min(replies.len() - 1)].clone())
    }

    /// Every request received so far, in arrival order.
    pub fn requests(&self) -> Vec<Recorded> {
        self.requests.lock().unwrap().clone()
    }
}

impl Drop for TestServer {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::SeqCst);
        // Wake the accept loop.
        let _ = TcpStream::connect(self.addr);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

fn serve(
    stream: TcpStream,
    handler: &Handler,
    requests: &Mutex<Vec<Recorded>>,
    counter: &AtomicUsize,
) {
    let mut reader = BufReader::new(match stream.try_clone() {
        Ok(s) => s,
        Err(_) => return,
    });
    let mut line = String::new();
    if reader.read_line(&mut line).unwrap_or(0) == 0 {
        return; // the wake-up connection, or a client that gave up
    }
    let mut parts = line.split_whitespace();
    let method = parts.next().unwrap_or("").to_string();
    let path = parts.next().unwrap_or("").to_string();
    let mut headers = Vec::new();
    loop {
        let mut h = String::new();
        if reader.read_line(&mut h).unwrap_or(0) == 0 {
            return;
        }
        let h = h.trim_end();
        if h.is_empty() {
            break;
        }
        if let Some((k, v)) = h.split_once(':') {
            headers.push((k.trim().to_string(), v.trim().to_string()));
        }
    }
    let find = |name: &str| {
        headers
            .iter()
            .find(|(k, _): &&(String, String)| k.eq_ignore_ascii_case(name))
            .map(|(_, v)| v.clone())
    };
    let mut body = Vec::new();
    if let Some(len) = find("content-length").and_then(|v| v.parse::<usize>().ok()) {
        body.resize(len, 0);
        if reader.read_exact(&mut body).is_err() {
            return;
        }
    } else if find("transfer-encoding").is_some_and(|v| v.contains("chunked")) {
        loop {
            let mut size = String::new();
            reader.read_line(&mut size).unwrap_or(0);
            let n = usize::from_str_radix(size.trim(), 16).unwrap_or(0);
            let mut chunk = vec![0; n + 2];
            if reader.read_exact(&mut chunk).is_err() {
                return;
            }
            if n == 0 {
                break;
            }
            body.extend_from_slice(&chunk[..n]);
        }
    }
    let recorded = Recorded {
        method,
        path,
        headers,
        body,
    };
    let index = counter.fetch_add(1, Ordering::SeqCst);
    requests.lock().unwrap().push(recorded.clone());
    let reply = handler(index, &recorded);
    std::thread::sleep(reply.delay);
    if reply.parts.is_empty() {
        write_whole(stream, &reply);
    } else {
        write_parts(stream, &reply);
    }
}

/// Writes `reply` with a `Content-Length`.
fn write_whole(stream: TcpStream, reply: &Reply) {
    let mut out = stream;
    let mut head = format!(
        "HTTP/1.1 {} X\r\nContent-Length: {}\r\nConnection: close\r\n",
        reply.status,
        reply.body.len()
    );
    for (k, v) in &reply.headers {
        head.push_str(&format!("{k}: {v}\r\n"));
    }
    head.push_str("\r\n");
    let _ = out.write_all(head.as_bytes());
    let _ = out.write_all(&reply.body);
    let _ = out.flush();
}

/// Writes `reply`'s parts in chunked encoding, pausing before each; a cut reply ends without
/// the last chunk.
fn write_parts(stream: TcpStream, reply: &Reply) {
    let mut out = stream;
    let mut head = format!(
        "HTTP/1.1 {} X\r\nTransfer-Encoding: chunked\r\nConnection: close\r\n",
        reply.status
    );
    for (k, v) in &reply.headers {
        head.push_str(&format!("{k}: {v}\r\n"));
    }
    head.push_str("\r\n");
    if out
        .write_all(head.as_bytes())
        .and_then(|()| out.flush())
        .is_err()
    {
        return;
    }
    for (pause, part) in &reply.parts {
        std::thread::sleep(*pause);
        let chunk = [format!("{:x}\r\n", part.len()).as_bytes(), part, b"\r\n"].concat();
        if out.write_all(&chunk).and_then(|()| out.flush()).is_err() {
            return;
        }
    }
    if reply.cut {
        let _ = out.shutdown(std::net::Shutdown::Both);
    } else {
        let _ = out.write_all(b"0\r\n\r\n");
        let _ = out.flush();
    }
}

/// A chat answer streamed in OpenAI's shape: one event with the role, one per piece of
/// content, one with `finish_reason` (`stop`), one with the token usage, then `data: [DONE]`.
pub fn openai_stream(model: &str, pieces: &[&str]) -> Vec<String> {
    let event = |v: Value| format!("data: {v}\n\n");
    let chunk = |delta: Value, finish: Value| {
        event(serde_json::json!({
            "id": "chatcmpl-S1", "object": "chat.completion.chunk", "created": 1764100000,
            "model": model,
            "choices": [{"index": 0, "delta": delta, "logprobs": null, "finish_reason": finish}]
        }))
    };
    let mut events = vec![chunk(
        serde_json::json!({"role": "assistant", "content": ""}),
        Value::Null,
    )];
    events.extend(
        pieces
            .iter()
            .map(|p| chunk(serde_json::json!({"content": p}), Value::Null)),
    );
    events.push(chunk(serde_json::json!({}), serde_json::json!("stop")));
    events.push(event(serde_json::json!({
        "id": "chatcmpl-S1", "object": "chat.completion.chunk", "created": 1764100000,
        "model": model, "choices": [],
        "usage": {"prompt_tokens": 90, "completion_tokens": pieces.len(), "total_tokens": 90 + pieces.len()}
    })));
    events.push("data: [DONE]\n\n".to_string());
    events
}

/// A chat completion in OpenAI's shape.
pub fn openai_completion(model: &str, content: &str) -> Value {
    serde_json::json!({
        "id": "chatcmpl-AbC123",
        "object": "chat.completion",
        "created": 1764100000,
        "model": model,
        "system_fingerprint": "fp_test",
        "choices": [{
            "index": 0,
            "message": {"role": "assistant", "content": content, "refusal": null, "annotations": []},
            "logprobs": null,
            "finish_reason": "stop"
        }],
        "usage": {"prompt_tokens": 120, "completion_tokens": 30, "total_tokens": 150,
                  "prompt_tokens_details": {"cached_tokens": 0}}
    })
}

/// A chat completion in vLLM's shape.
pub fn vllm_completion(model: &str, content: &str) -> Value {
    serde_json::json!({
        "id": "chatcmpl-9f1c",
        "object": "chat.completion",
        "created": 1764100001,
        "model": model,
        "choices": [{
            "index": 0,
            "message": {"role": "assistant", "reasoning_content": null, "content": content,
                        "tool_calls": []},
            "logprobs": null,
            "finish_reason": "stop",
            "stop_reason": null
        }],
        "usage": {"prompt_tokens": 80, "total_tokens": 100, "completion_tokens": 20,
                  "prompt_tokens_details": null},
        "prompt_logprobs": null,
        "kv_transfer_params": null
    })
}

/// A chat completion in Ollama's OpenAI-compatible shape.
pub fn ollama_completion(model: &str, content: &str) -> Value {
    serde_json::json!({
        "id": "chatcmpl-512",
        "object": "chat.completion",
        "created": 1764100002,
        "model": model,
        "system_fingerprint": "fp_ollama",
        "choices": [{"index": 0, "message": {"role": "assistant", "content": content},
                     "finish_reason": "stop"}],
        "usage": {"prompt_tokens": 50, "completion_tokens": 10, "total_tokens": 60}
    })
}

/// A chat completion in llama.cpp server's shape (with its `timings`).
pub fn llamacpp_completion(model: &str, content: &str) -> Value {
    serde_json::json!({
        "choices": [{"finish_reason": "stop", "index": 0,
                     "message": {"role": "assistant", "content": content}}],
        "created": 1764100003,
        "model": model,
        "system_fingerprint": "b4500-abc",
        "object": "chat.completion",
        "usage": {"completion_tokens": 12, "prompt_tokens": 40, "total_tokens": 52},
        "id": "chatcmpl-xyz",
        "timings": {"prompt_n": 40, "prompt_ms": 50.1, "predicted_n": 12, "predicted_ms": 90.2}
    })
}

/// An image answer in OpenAI's shape (`/v1/images/generations` and `/v1/images/edits`): the
/// image as `data[0].b64_json`.
pub fn openai_image(image: &scenethesis_models::ImageData) -> Value {
    serde_json::json!({
        "created": 1764100000,
        "data": [{"b64_json": image.to_base64()}],
        "usage": {"input_tokens": 300, "output_tokens": 4160, "total_tokens": 4460}
    })
}
