//! The generator's intermediate representation, the bottom layer every stage shares: what a
//! model derivation produces ([`Formula`]s of [`Output`]s, Taylor [`System`]s) and how generated
//! functions take their inputs ([`Group`]s of declared symbols). It depends on the expression
//! graph only; `model` fills it, `optimize`, `emit` and `taylor` read it.

use crate::expr::{ExprId, Symbol};

/// One output of a formula.
pub struct Output {
    /// Field name in the output struct.
    pub name: String,
    /// One-line meaning.
    pub doc: String,
    /// Its expression.
    pub expr: ExprId,
}

/// A generated function: inputs, outputs and where it comes from.
pub struct Formula {
    /// Function name.
    pub name: String,
    /// What it computes (the doc comment's first line).
    pub summary: String,
    /// Where the formula is stated (`docs/MODEL.md` section).
    pub source: String,
    /// How the generator derived it.
    pub derivation: String,
    /// Used only by the generator's verification tests: emitted `#[doc(hidden)]`.
    pub test_only: bool,
    /// Output struct name (a declared [`Group`] when other formulas take it as input).
    pub output_type: String,
    /// Outputs, in struct order.
    pub outputs: Vec<Output>,
}

/// An input struct of the generated functions: its type, the argument name functions give it,
/// its doc line and its fields as (symbol, field, meaning).
#[derive(Clone)]
pub struct Group {
    /// Struct name in the generated code.
    pub ty: &'static str,
    /// Argument name of the struct in generated signatures.
    pub arg: &'static str,
    /// Doc line of the struct.
    pub doc: &'static str,
    /// (symbol, field name, meaning), in struct order.
    pub fields: &'static [(&'static str, &'static str, &'static str)],
    /// The path of a struct the runtime defines itself (not emitted; signatures name the path),
    /// `None` for a struct the generated code declares.
    pub external: Option<&'static str>,
}

/// An ODE system whose Taylor recurrences are generated.
pub struct System {
    /// Name of the generated module (`contact_taylor`, …).
    pub name: String,
    /// What the system is (doc comment).
    pub summary: String,
    /// Where the field is stated (`docs/MODEL.md` section).
    pub source: String,
    /// States: the symbol and its rate d/dτ, in the order the runtime stores them.
    pub states: Vec<(Symbol, ExprId)>,
    /// Observed quantities (switch functions): name, doc line, expression.
    pub observed: Vec<(String, String, ExprId)>,
}
