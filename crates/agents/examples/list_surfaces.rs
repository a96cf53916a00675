//! Lists support-surface polygons of the named catalog categories.
fn main() {
    for name in std::env::args().skip(1) {
        let c = scenethesis_assets::catalog::category(&name).expect("category");
        for seed in [1, 2] {
            let a = scenethesis_assets::catalog::generate(c, seed);
            println!("{name} seed {seed} size {:?}", a.info.size);
            for s in &a.info.support_surfaces {
                println!("   {} {:?} h{} clear {:?} poly {:?}", s.name, s.kind, s.height, s.clearance, s.polygon);
            }
        }
    }
}
