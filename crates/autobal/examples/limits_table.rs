//! Prints the table of input ranges (`autobal::limits`) that docs/reference/robustness.md shows:
//! `cargo run -p autobal --example limits_table`.
fn main() {
    print!("{}", autobal::limits::markdown_table());
}
