//! Prints the domain of validity as the README's Markdown table.
fn main() {
    print!("{}", ridelab::domain::markdown_table());
}
