//! The main job (`softshadow` with no arguments) runs, and every kernel in
//! its self-check is within its budget of the closed form.

use std::process::Command;

#[test]
fn default_run_passes_its_self_check() {
    let out = Command::new(env!("CARGO_BIN_EXE_softshadow"))
        .output()
        .expect("the softshadow binary runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "exit {:?}\n{stdout}", out.status);
    assert!(stdout.contains(" 0 over budget"), "{stdout}");
    assert!(!stdout.contains("NaN"), "{stdout}");
}
