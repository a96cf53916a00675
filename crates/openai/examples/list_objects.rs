//! Asks an OpenAI-compatible endpoint which objects a scene needs, as schema-checked JSON.
//!
//! ```text
//! OPENAI_BASE_URL=http://127.0.0.1:11434/v1 SCENETHESIS_LLM_MODEL=llama3.2 \
//!     cargo run -p scenethesis-openai --example list_objects -- "a pharmacy" [CACHE_DIR]
//! ```
//!
//! Configuration comes from the environment (`OPENAI_BASE_URL`, `OPENAI_API_KEY`,
//! `SCENETHESIS_LLM_MODEL`). With a `CACHE_DIR`, answers are recorded there and a second run
//! replays them without contacting the server.

use std::process::ExitCode;

use scenethesis_models::{
    CacheMode, Cached, ChatModel, ChatRequest, JsonSchema, Message, ResponseCache,
};
use scenethesis_openai::{ClientConfig, OpenAiClient, Overrides};
use serde_json::json;

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let prompt = args.next().unwrap_or_else(|| "a pharmacy".to_string());
    let cache_dir = args.next();

    let config = ClientConfig::resolve(&Overrides::default(), None)?;
    let client = OpenAiClient::new(config)?;
    let llm = client.llm()?;
    let meter = llm.meter().clone();
    let model: Box<dyn ChatModel> = match cache_dir {
        Some(dir) => Box::new(
            Cached::new(llm, ResponseCache::open(dir, CacheMode::ReadWrite)?)
                .with_meter(meter.clone()),
        ),
        None => Box::new(llm),
    };

    let schema = JsonSchema::new(
        "scene_objects",
        json!({
            "type": "object",
            "additionalProperties": false,
            "required": ["anchor", "objects"],
            "properties": {
                "anchor": {"type": "string", "minLength": 1},
                "objects": {
                    "type": "array",
                    "minItems": 5,
                    "items": {
                        "type": "object",
                        "additionalProperties": false,
                        "required": ["name", "count"],
                        "properties": {
                            "name": {"type": "string", "minLength": 1},
                            "count": {"type": "integer", "minimum": 1, "maximum": 40}
                        }
                    }
                }
            }
        }),
    )?;
    let request = ChatRequest::structured(
        vec![
            Message::system("You are an interior planner. Name the furniture and objects of a scene."),
            Message::user(format!("Which objects, and how many of each, belong in {prompt}? Name the central object as the anchor.")),
        ],
        schema,
    );
    let answer = model.chat(&request)?;
    println!("{}", serde_json::to_string_pretty(&answer.json)?);
    for note in &answer.notes {
        eprintln!("note: {note}");
    }
    eprintln!("usage: {}", serde_json::to_string(&meter.snapshot())?);
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            let mut source = e.source();
            while let Some(s) = source {
                eprintln!("  caused by: {s}");
                source = s.source();
            }
            ExitCode::FAILURE
        }
    }
}
