//! `autobal report --quick` on real balls (contact, rolling resistance: issue 18 §2): the
//! stationary state has no linearisation, so the sections that analyse one say so in one line
//! (the typed `autobal::Error::NoLinearisation`'s message) and the report is written; the
//! sections that simulate still run.

use autobal_commands::command::{Command as _, ConfigSource};
use autobal_commands::report;
use std::path::Path;

fn report_of(config: &str, sets: &[&str], name: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let args = report::Args { config: ConfigSource::file(Some(&root.join(config)), &sets), out: dir, quick: true, papers: false };
    let out = args.run(&autobal::control::Control::none()).unwrap_or_else(|e| panic!("{config}: {e:#}"));
    std::fs::read_to_string(out.index).unwrap()
}

#[test]
fn a_quick_report_on_real_balls_says_which_sections_cannot_linearise() {
    for (config, set, name) in [
        ("examples/planar.toml", "planar.contact=true", "real-balls-planar"),
        ("examples/spatial_two_plane.toml", "balancer.contact=true", "real-balls-spatial"),
    ] {
        let page = report_of(config, &[set], name);
        // at least the stability section says so, each place in one line saying what was not
        // computed (a section not applicable, critical speeds not located, a map not computed)
        let said = page.matches("no linearisation: ").count();
        assert!(said >= 1, "{config}: no section names the missing linearisation");
        for line in page.lines().filter(|l| l.contains("no linearisation: ")) {
            assert!(["Not applicable", "Not located", "not computed"].iter().any(|w| line.contains(w)), "{config}: {line}");
        }
    }
}
