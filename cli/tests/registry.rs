//! The registry is the one list of methods: every registered name parses,
//! prints and round-trips with every option; `--help`, the "available"
//! message and the README's table list exactly the registered methods;
//! the default set and the report settings come from it.

use softshadow::method::{self, registry, REGISTRY};
use softshadow::scene::LightKind;
use std::process::Command;

#[test]
fn every_options_table_keeps_its_promises() {
    for e in REGISTRY {
        e.check_options_table()
            .unwrap_or_else(|err| panic!("{}: {err}", e.name));
    }
}

#[test]
fn every_registered_setting_parses_prints_and_round_trips() {
    let mut settings = 0;
    for e in REGISTRY {
        for name in e.default_run.iter().chain(e.compare) {
            let m = method::parse(name).unwrap_or_else(|err| panic!("{name}: {err}"));
            assert_eq!(
                m.name(),
                *name,
                "a registered setting is written canonically"
            );
            let again = method::parse(&m.name()).unwrap();
            assert_eq!(format!("{again:?}"), format!("{m:?}"), "{name}");
            settings += 1;
        }
        let m = method::parse(e.default_run.first().unwrap_or(&e.name)).unwrap();
        assert_eq!(
            m.lights(),
            e.lights,
            "{}: the method handles what the registry says",
            e.name
        );
        if e.usage() == e.name {
            assert_eq!(method::parse(e.name).unwrap().name(), e.name);
        }
    }
    assert!(settings > 10);
}

#[test]
fn an_unknown_method_is_refused_with_every_registered_one() {
    let err = method::parse("no-such-method").unwrap_err().to_string();
    for e in REGISTRY {
        assert!(err.contains(&e.usage()), "{err} lacks {}", e.usage());
        assert!(registry::available().contains(&e.usage()));
    }
}

#[test]
fn the_default_set_is_the_registry_s_for_each_light_kind() {
    for &kind in LightKind::ALL {
        let names: Vec<String> = method::default_set(kind).iter().map(|m| m.name()).collect();
        let want: Vec<&str> = REGISTRY
            .iter()
            .filter(|e| e.handles(kind))
            .flat_map(|e| e.default_run.iter().copied())
            .collect();
        assert_eq!(names, want, "{kind}");
        assert!(names.iter().any(|n| n == "exact"), "{kind}");
    }
    assert!(!method::default_set(LightKind::Segment)
        .iter()
        .any(|m| m.name() == "sism"));
}

#[test]
fn help_lists_every_method_with_its_options() {
    let out = Command::new(env!("CARGO_BIN_EXE_softshadow"))
        .arg("--help")
        .output()
        .unwrap();
    let help = String::from_utf8_lossy(&out.stdout);
    for e in REGISTRY {
        assert!(help.contains(&e.usage()), "--help lacks {}", e.usage());
        for o in e.options() {
            assert!(help.contains(&o), "--help lacks {o}");
        }
    }
    let out = Command::new(env!("CARGO_BIN_EXE_softshadow"))
        .args(["render", "--help"])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&out.stdout).contains("exact-union"));
}

#[test]
fn the_readme_s_table_lists_exactly_the_registered_methods() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md")).unwrap();
    let start = readme
        .find("| method | lights | what |")
        .expect("the README's table of methods");
    let rows: Vec<&str> = readme[start..]
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with("| `"))
        .map(|l| l.split('`').nth(1).unwrap())
        .collect();
    let registered: Vec<String> = REGISTRY.iter().map(|e| e.usage()).collect();
    assert_eq!(rows, registered);
}
