//! The parameter table as the generator reads it: the same file as the runtime's
//! (`runtime/params/entries.rs`, included below), read through this module's own
//! `parameter_table!` macro into [`MODEL`]. So the generated formulas' parameters are the table's
//! entries by name (`speed_ratio`, `k_xy`, …): the model statement reads them with
//! `Model::var("k_xy")`, the generated `ModelParams` has a field of that name, and the generated
//! `model_params` copies it from the runtime's `Params` field of the same name. Nothing maps one
//! vocabulary onto another, so no pair can be swapped; a name the table does not have fails the
//! build naming it (`symbols.rs`).

/// A valid range as the table states it (the generator needs only its presence).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// Lower bound.
    pub min: f64,
    /// Upper bound (included).
    pub max: f64,
}

impl Range {
    /// `[min, max]`.
    pub const fn closed(min: f64, max: f64) -> Self {
        Range { min, max }
    }

    /// `(min, max]`.
    pub const fn above(min: f64, max: f64) -> Self {
        Range { min, max }
    }
}

/// One model parameter of the table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Entry {
    /// Its name: the runtime's `Params` field, the CLI's `--set` name and the symbol the model
    /// statement reads.
    pub name: &'static str,
    /// The paper's symbol.
    pub symbol: &'static str,
    /// What it is.
    pub doc: &'static str,
}

macro_rules! parameter_table {
    (
        model { $( $mvar:ident $mname:ident $msym:literal = $mdef:expr, $mrange:expr, $mdoc:literal; )* }
        start { $( $svar:ident $sname:ident $ssym:literal = $sdef:expr, $srange:expr, $sdoc:literal,
                   $($spath:ident).+; )* }
    ) => {
        /// The table's model parameters, in table order.
        pub const MODEL: &[Entry] = &[
            $( Entry { name: stringify!($mname), symbol: $msym, doc: $mdoc }, )*
        ];
        // The start entries and every range are the runtime's business (validation).
        const _: &[Range] = &[$( $mrange, )* $( $srange, )*];
    };
}

include!("../../../runtime/params/entries.rs");

/// The table entry named `name`.
pub fn entry(name: &str) -> Option<&'static Entry> {
    MODEL.iter().find(|e| e.name == name)
}
