//! One table for categories: retrieval and the offline planner read the same rows of
//! `crates/procedural/data/categories.toml`, so every category name and every word of the table
//! resolves to the same category on both sides.

use scenethesis_agents::Knowledge;
use scenethesis_procedural::catalog;
use scenethesis_retrieval::AssetIndex;

#[test]
fn retrieval_and_the_planner_resolve_every_word_to_the_same_category() {
    let index = AssetIndex::builtin();
    let knowledge = Knowledge::builtin();
    let mut failures = Vec::new();
    let names = catalog::categories().map(|c| (c.name.replace('_', " "), c.name));
    for (word, owner) in names.chain(catalog::words().map(|(w, c)| (w.to_owned(), c))) {
        let planned = knowledge.category_of_phrase(&word);
        let retrieved = index.search(&word, 1, 0);
        let retrieved = retrieved.first().map(|c| c.category.as_str());
        if planned != Some(owner) || retrieved != Some(owner) {
            failures.push(format!(
                "`{word}` (table: {owner}): planner {planned:?}, retrieval {retrieved:?}"
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} words resolve differently:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_planner_knows_exactly_the_registered_categories() {
    let knowledge = Knowledge::builtin();
    let planned: Vec<&str> = knowledge.category_names().collect();
    let mut registered: Vec<&str> = catalog::categories().map(|c| c.name).collect();
    registered.sort_unstable();
    assert_eq!(planned, registered);
    // Placement and the planner's mount agree except where the table says otherwise.
    for c in catalog::categories() {
        let prior = knowledge.prior(c.name).unwrap();
        let row = &catalog::table()[c.name];
        let mount = format!("{:?}", prior.mount).to_lowercase();
        let placement = format!("{:?}", c.placement).to_lowercase();
        assert!(
            mount == placement || row.plan.contains_key("mount"),
            "{}: planner mount {mount}, placement {placement}, no override in the table",
            c.name
        );
        assert_eq!(prior.words.len(), c.synonyms.len(), "{}", c.name);
    }
}
