//! The parameter table: every model parameter and initial-state value, stated once with its name,
//! paper symbol, default, valid range and meaning (`docs/MODEL.md §9`). The [`Params`] struct, the
//! [`Parameter`] enum, access by name, validation, presets, the CLI's `--set`/TOML/`params`
//! listing and the C ABI's setters are all derived from it: adding a parameter is one entry.
//! The entries themselves, and why each range is what it is, are in `entries.rs`: the one file
//! both this module and the generator (`codegen/src/model/parameters.rs`) read.

use super::{Problem, Range};

/// Declares the table: model parameters become [`Params`] fields, initial values name their
/// place in [`Problem`]. Each entry: `Variant name "symbol" = default, range, "meaning";`.
macro_rules! parameter_table {
    (
        model { $( $mvar:ident $mname:ident $msym:literal = $mdef:expr, $mrange:expr, $mdoc:literal; )* }
        start { $( $svar:ident $sname:ident $ssym:literal = $sdef:expr, $srange:expr, $sdoc:literal,
                   $($spath:ident).+; )* }
    ) => {
        /// Parameters of the rotor–stator model (`docs/MODEL.md §1`, ranges in `docs/MODEL.md §9`),
        /// generated from the parameter table (`params/table.rs`).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct Params {
            $( #[doc = concat!($msym, ": ", $mdoc, ".")] pub $mname: f64, )*
        }

        /// One entry of the parameter table: a model parameter or an initial-state value. The
        /// names are the public field names, the CLI's `--set` names and the C ABI's names.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Parameter {
            $( #[doc = $mdoc] $mvar, )*
            $( #[doc = $sdoc] $svar, )*
        }

        impl Parameter {
            /// Every parameter in table order (the discriminants are the indices).
            pub const ALL: [Parameter; Parameter::COUNT] =
                [$(Parameter::$mvar,)* $(Parameter::$svar,)*];
            /// The number of table entries.
            pub const COUNT: usize = [$(stringify!($mvar),)* $(stringify!($svar),)*].len();
            /// The number of model parameters (the leading entries, the fields of [`Params`]).
            pub const MODEL_COUNT: usize = [$(stringify!($mvar),)*].len();

            /// The parameter's valid range (the table's; [`Self::info`] without the texts).
            pub const fn range(self) -> Range {
                match self {
                    $( Parameter::$mvar => $mrange, )*
                    $( Parameter::$svar => $srange, )*
                }
            }

            /// The parameter's table entry.
            pub const fn info(self) -> Info {
                match self {
                    $( Parameter::$mvar => Info { name: stringify!($mname), symbol: $msym,
                        default: $mdef, range: $mrange, doc: $mdoc }, )*
                    $( Parameter::$svar => Info { name: stringify!($sname), symbol: $ssym,
                        default: $sdef, range: $srange, doc: $sdoc }, )*
                }
            }

            /// The parameter's value in a problem.
            pub const fn get(self, p: &Problem) -> f64 {
                match self {
                    $( Parameter::$mvar => p.params.$mname, )*
                    $( Parameter::$svar => p.$($spath).+, )*
                }
            }

            /// Set the parameter's value in a problem (not validated: call [`Problem::validate`]).
            pub const fn set(self, p: &mut Problem, value: f64) {
                match self {
                    $( Parameter::$mvar => p.params.$mname = value, )*
                    $( Parameter::$svar => p.$($spath).+ = value, )*
                }
            }
        }

        impl Params {
            /// The table's defaults (the `paper` preset).
            pub const DEFAULT: Params = Params { $( $mname: $mdef, )* };

            /// The values in table order (the first [`Parameter::MODEL_COUNT`] entries of
            /// [`Parameter::ALL`]).
            pub const fn values(&self) -> [f64; Parameter::MODEL_COUNT] {
                [$( self.$mname, )*]
            }

            /// The parameters with `values` in table order (the inverse of [`Params::values`]):
            /// what a caller that holds the table as an array (the C ABI's struct) converts
            /// through, so that no field is copied by hand.
            pub const fn from_values(values: [f64; Parameter::MODEL_COUNT]) -> Params {
                let [$( $mname, )*] = values;
                Params { $( $mname, )* }
            }
        }

        impl Problem {
            /// Every table value of the problem, in the order of [`Parameter::ALL`].
            pub const fn values(&self) -> [f64; Parameter::COUNT] {
                [$( self.params.$mname, )* $( self.$($spath).+, )*]
            }
        }
    };
}

/// What the table says about one parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Info {
    /// Public name, e.g. `speed_ratio`.
    pub name: &'static str,
    /// The paper's symbol, e.g. `η`.
    pub symbol: &'static str,
    /// Default value (the `paper` preset's).
    pub default: f64,
    /// Valid values.
    pub range: Range,
    /// One line saying what it is and in which unit.
    pub doc: &'static str,
}

include!("entries.rs");
