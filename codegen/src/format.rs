//! Formatting: the emitted tokens are parsed back with `syn` (so a malformed emission fails the
//! build with a parse error, not a confusing compile error in the runtime) and printed with
//! `prettyplease` for people to read.

use proc_macro2::TokenStream;

/// Parse `tokens` as a Rust file and pretty-print it.
pub fn format_file(tokens: TokenStream) -> Result<String, syn::Error> {
    let file: syn::File = syn::parse2(tokens)?;
    Ok(prettyplease::unparse(&file))
}
