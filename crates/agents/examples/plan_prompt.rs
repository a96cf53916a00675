//! Prints the plan and guided layout summary for a prompt: `cargo run -p scenethesis-agents
//! --example plan_prompt -- "a gym room" 7`.

use scenethesis_agents::{
    CatalogAssets, Guide, KnowledgePlanner, PlanRequest, Planner, ProceduralGuide,
};

fn main() {
    let mut args = std::env::args().skip(1);
    let prompt = args.next().unwrap_or_else(|| "a gym room".into());
    let seed: u64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(0);
    let planner = KnowledgePlanner::new();
    let available: Vec<String> = scenethesis_procedural::catalog::categories()
        .map(|c| c.name.to_owned())
        .collect();
    let request = PlanRequest::new(prompt, available, seed);
    let plan = match planner.plan(&request) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    };
    println!(
        "scene type {} ({:?}), room {:?}, anchor {}",
        plan.scene_type, plan.archetypes, plan.room_size, plan.anchor
    );
    println!("{}", plan.description);
    for o in &plan.objects {
        println!(
            "  {:<20} {:<12?} {:<13} {:<18} {:?} {:?}{}",
            o.id,
            o.layer,
            o.support.as_str(),
            o.parent.to_string(),
            o.zone,
            o.relations
                .iter()
                .map(|r| format!("{} {}", r.kind, r.target))
                .collect::<Vec<_>>(),
            if o.hard { " HARD" } else { "" }
        );
    }
    for c in &plan.constraints {
        println!(
            "  constraint: {} {} {:?} ({})",
            c.subject, c.kind, c.target, c.phrase
        );
    }
    for n in &plan.notes {
        println!("  note: {n}");
    }
    let layout = ProceduralGuide::default()
        .layout(&plan, &CatalogAssets::new(seed), seed)
        .expect("layout");
    println!(
        "placed {} of {} objects; walk {:.4}; door {}; unreachable {:?}",
        layout.scene.objects.len(),
        plan.objects.len(),
        layout.walkway.walk_ratio,
        layout.walkway.door_reachable,
        layout.walkway.unreachable
    );
    for d in &layout.dropped {
        println!("  dropped {}: {}", d.id, d.reason);
    }
    if let Some(path) = args.next() {
        layout
            .scene
            .write_json_atomic(std::path::Path::new(&path))
            .expect("write");
    }
}
