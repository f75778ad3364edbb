//! The `softshadow` command-line program.
fn main() {}
