//! Emission of a [`System`]'s recurrences: a module with the system's layout constants, its
//! time-constant sub-expressions as an ordinary generated formula (`constants`), and the
//! recurrences as straight-line code over the operations, `order0` (values) and `order`
//! (coefficient n ≥ 1 of every operation, then coefficient n + 1 of every state).

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use super::{Coef, Op, Program};
use crate::emit::{Emitted, emit_formula};
use crate::expr::Graph;
use crate::ir::{Formula, Group, Output, System};
use crate::optimize::OpCounts;

/// The emitted module of one system, with what the file header reports.
pub struct EmittedSystem {
    /// `pub mod name { … }`.
    pub tokens: TokenStream,
    /// The constants formula's counts (before and after CSE) and the input structs it takes.
    pub constants: Emitted,
    /// Operation counts of `order0`.
    pub order0: OpCounts,
    /// Operation counts of `order` at order n, as (fixed part, part per unit of n).
    pub per_order: (OpCounts, OpCounts),
    /// Number of series.
    pub series: usize,
}

fn ident(name: &str) -> Ident {
    Ident::new(name, Span::call_site())
}

fn index(i: usize) -> Literal {
    Literal::usize_unsuffixed(i)
}

/// `coef · operand` as tokens (`operand` already a token stream); counts the multiplication.
fn scaled(c: Coef, operand: TokenStream, counts: &mut OpCounts) -> (TokenStream, bool) {
    match c {
        Coef::Literal(1.0) => (operand, false),
        Coef::Literal(-1.0) => (operand, true),
        Coef::Literal(v) => {
            counts.mul += 1;
            let lit = Literal::f64_unsuffixed(v.abs());
            (quote!(#lit * #operand), v < 0.0)
        }
        Coef::Constant(k) => {
            counts.mul += 1;
            let f = ident(&format!("k{k}"));
            (quote!(k.#f * #operand), false)
        }
    }
}

/// A signed sum of terms, added in the order given (the caller puts the terms whose values are
/// known first at the front: the last additions are the ones on the chain).
fn sum(terms: Vec<(TokenStream, bool)>, counts: &mut OpCounts) -> TokenStream {
    let mut out = TokenStream::new();
    for (k, (t, neg)) in terms.into_iter().enumerate() {
        if k == 0 {
            out.extend(if neg { quote!(-#t) } else { t });
        } else {
            counts.add += 1;
            out.extend(if neg { quote!(- #t) } else { quote!(+ #t) });
        }
    }
    if out.is_empty() {
        out = quote!(0.0);
    }
    out
}

/// A linear combination's terms in the order their coefficients become known within an order:
/// by series index (the states, set at the end of the previous order, first; every other series
/// after the ones it reads), so that the last addition waits only for the newest term.
fn by_availability(terms: &[(Coef, usize)]) -> Vec<(Coef, usize)> {
    let mut sorted = terms.to_vec();
    sorted.sort_by_key(|&(_, j)| j);
    sorted
}

/// Which operations the observed series depend on (themselves included): all an order needs to
/// compute when it only extends the switch functions (the last order of an expansion: the
/// states' polynomials end one order earlier).
fn observed_closure(program: &Program) -> Vec<bool> {
    let mut needed = vec![false; program.ops.len()];
    let mut stack: Vec<usize> = program.observed.clone();
    while let Some(i) = stack.pop() {
        if needed.get(i).copied().unwrap_or(true) {
            continue;
        }
        needed[i] = true;
        match &program.ops[i] {
            Op::State => {}
            Op::Linear { terms, .. } => stack.extend(terms.iter().map(|t| t.1)),
            Op::Product(a, b) => stack.extend([*a, *b]),
            Op::Square(a) | Op::Power(a, _) | Op::Sqrt(a) | Op::HalfPower(a, _) => stack.push(*a),
        }
    }
    needed
}

/// The body of an order-n function: coefficient n of every operation `include`s (in program
/// order), then, with `states`, each state's coefficient n + 1; with the operation counts as
/// (fixed part, part per unit of n).
fn order_body(
    program: &Program,
    include: &[bool],
    states: bool,
) -> (TokenStream, OpCounts, OpCounts) {
    let mut fixed = OpCounts::default();
    let mut per_n = OpCounts::default();
    let mut body = TokenStream::new();
    for (i, op) in program.ops.iter().enumerate().skip(program.states) {
        if !include.get(i).copied().unwrap_or(false) {
            continue;
        }
        let sr = |j: usize| {
            let j = index(j);
            quote!(&s[#j])
        };
        let value = match op {
            Op::State => unreachable!("states come first"),
            Op::Linear { terms, .. } => {
                let parts = by_availability(terms)
                    .iter()
                    .map(|&(c, j)| {
                        let j = index(j);
                        scaled(c, quote!(ts::at(&s[#j], N)), &mut fixed)
                    })
                    .collect();
                sum(parts, &mut fixed)
            }
            Op::Product(a, b) => {
                per_n.mul += 1;
                per_n.add += 1;
                fixed.mul += 1;
                // The operand computed later in the order second (its coefficient n is the
                // kernel's last term).
                let (a, b) = (sr(*a.min(b)), sr(*a.max(b)));
                quote!(ts::product::<N>(#a, #b))
            }
            Op::Square(a) => {
                // n/2 products, doubled, plus the middle term.
                per_n.mul += 1;
                fixed.mul += 2;
                let a = sr(*a);
                quote!(ts::square::<N>(#a))
            }
            Op::Power(a, -1) => {
                per_n.mul += 1;
                per_n.add += 1;
                fixed.mul += 1;
                let (a, r) = (sr(*a), sr(i));
                quote!(ts::reciprocal::<N>(#a, #r))
            }
            Op::Power(a, p) => {
                per_n.mul += 3;
                per_n.add += 1;
                fixed.div += 1;
                let (a, r) = (sr(*a), sr(i));
                let p = Literal::i32_unsuffixed(*p);
                quote!(ts::power::<N>(#a, #r, #p))
            }
            Op::Sqrt(a) => {
                per_n.mul += 1;
                fixed.div += 1;
                fixed.add += 1;
                let (a, r) = (sr(*a), sr(i));
                quote!(ts::sqrt::<N>(#a, #r))
            }
            Op::HalfPower(a, p) => {
                per_n.mul += 2;
                per_n.add += 1;
                fixed.div += 1;
                let (a, r) = (sr(*a), sr(i));
                let p = Literal::i32_unsuffixed(*p);
                quote!(ts::half_power::<N>(#a, #r, #p))
            }
        };
        let i = index(i);
        body.extend(quote!(let v = #value; ts::set(&mut s[#i], N, v);));
    }
    if states {
        for (state, &rate) in program.rates.iter().enumerate() {
            fixed.mul += 1;
            let (st, r) = (index(state), index(rate));
            body.extend(quote!(
                let v = ts::at(&s[#r], N) * ts::inverse::<N>();
                ts::set(&mut s[#st], N + 1, v);
            ));
        }
    }
    (body, fixed, per_n)
}

/// Emit `system` (decomposed as `program`) as a module; `groups` resolves the constants'
/// input symbols.
/// Whether `system` is a rub station's (a rotor from matrices, `model/station.rs`), stored apart
/// from the planar model's systems.
pub fn is_station(system: &System) -> bool {
    system.name.starts_with("station_")
}

pub fn emit_system(
    g: &Graph,
    system: &System,
    program: &Program,
    groups: &'static [Group],
) -> EmittedSystem {
    let constants = Formula {
        name: "constants".to_owned(),
        summary: format!(
            "The time-constant sub-expressions of the {} recurrences (parameters and their combinations), computed once per segment.",
            system.name
        ),
        source: system.source.clone(),
        derivation: "the sub-expressions of the field that depend on no state.".to_owned(),
        test_only: false,
        output_type: "Constants".to_owned(),
        outputs: program
            .constants
            .iter()
            .enumerate()
            .map(|(k, &e)| Output {
                name: format!("k{k}"),
                doc: format!("time-constant sub-expression {k}"),
                expr: e,
            })
            .collect(),
    };
    let constants = emit_formula(g, &constants, groups);

    // order 0: values.
    let mut c0 = OpCounts::default();
    let mut body0 = TokenStream::new();
    for (i, op) in program.ops.iter().enumerate().skip(program.states) {
        let at = |j: usize| {
            let j = index(j);
            quote!(s[#j][0])
        };
        let value = match op {
            Op::State => unreachable!("states come first"),
            Op::Linear { constant, terms } => {
                let mut parts: Vec<(TokenStream, bool)> = Vec::new();
                if let Some(c) = constant {
                    parts.push(match *c {
                        Coef::Literal(v) => {
                            let lit = Literal::f64_unsuffixed(v.abs());
                            (quote!(#lit), v < 0.0)
                        }
                        Coef::Constant(k) => {
                            let f = ident(&format!("k{k}"));
                            (quote!(k.#f), false)
                        }
                    });
                }
                for &(c, j) in &by_availability(terms) {
                    parts.push(scaled(c, at(j), &mut c0));
                }
                sum(parts, &mut c0)
            }
            Op::Product(a, b) => {
                c0.mul += 1;
                let (a, b) = (at(*a), at(*b));
                quote!(#a * #b)
            }
            Op::Square(a) => {
                c0.mul += 1;
                let a = at(*a);
                quote!(#a * #a)
            }
            Op::Power(a, -1) => {
                c0.div += 1;
                let a = at(*a);
                quote!(1.0 / #a)
            }
            Op::Power(a, p) => {
                c0.transcendental += 1;
                let a = at(*a);
                let p = Literal::i32_unsuffixed(*p);
                quote!(ts::powi(#a, #p))
            }
            Op::Sqrt(a) => {
                c0.sqrt += 1;
                let a = at(*a);
                quote!(m::sqrt(#a))
            }
            Op::HalfPower(a, -1) => {
                c0.sqrt += 1;
                c0.div += 1;
                let a = at(*a);
                quote!(1.0 / m::sqrt(#a))
            }
            Op::HalfPower(a, p) => {
                c0.sqrt += 1;
                c0.transcendental += 1;
                let a = at(*a);
                let p = Literal::i32_unsuffixed(*p);
                quote!(ts::powi(m::sqrt(#a), #p))
            }
        };
        let i = index(i);
        body0.extend(quote!(s[#i][0] = #value;));
    }
    for (state, &rate) in program.rates.iter().enumerate() {
        let (st, r) = (index(state), index(rate));
        body0.extend(quote!(s[#st][1] = s[#r][0];));
    }

    // order n ≥ 1: every operation, then the states' next coefficient; and the last order,
    // only what the observed series need.
    let every: Vec<bool> = vec![true; program.ops.len()];
    let (body, fixed, per_n) = order_body(program, &every, true);
    let (last, _, _) = order_body(program, &observed_closure(program), false);

    let name = ident(&system.name);
    let summary = format!(" {}", system.summary);
    let source = format!(" Source: {}.", system.source);
    let series = index(program.ops.len());
    let states = index(program.states);
    let mut observed = TokenStream::new();
    for ((oname, doc, _), &i) in system.observed.iter().zip(&program.observed) {
        let c = ident(&oname.to_uppercase());
        let d = format!(" The series of {doc}.");
        let i = index(i);
        observed.extend(quote!(#[doc = #d] pub const #c: usize = #i;));
    }
    let ctokens = constants.tokens.clone();
    // A rub station's systems (rotors from matrices) have their own storage, so that the planar
    // model's storage is not sized by them (`TAYLOR_SERIES_MAX`, `STATION_TAYLOR_SERIES_MAX`).
    let storage = if is_station(system) {
        quote!(ts::StationSeries)
    } else {
        quote!(ts::Series)
    };
    let tokens = quote! {
        #[doc = #summary]
        #[doc = ""]
        #[doc = #source]
        #[doc = " Generated Taylor-coefficient recurrences (automatic differentiation of the field's"]
        #[doc = " elementary operations): `order0` evaluates every operation at the expansion point,"]
        #[doc = " `order` its coefficient n ≥ 1 from the lower ones, then each state's coefficient n + 1."]
        pub mod #name {
            #[allow(unused_imports)]
            use super::*;
            #[allow(unused_imports)]
            use crate::math as m;
            use crate::taylor::kernels as ts;

            /// Series the recurrences use (states first).
            pub const SERIES: usize = #series;
            /// States, stored first: x, y, x', y', cos θ, sin θ.
            pub const STATES: usize = #states;
            #observed

            #ctokens

            /// Every operation at the expansion point (order 0; the states' order 0 set by the
            /// caller), and every state's coefficient 1.
            #[inline]
            pub fn order0(k: &Constants, s: &mut #storage) {
                let _ = k;
                #body0
            }

            /// Coefficient `N` ≥ 1 of every operation (coefficients below `N` computed), then
            /// coefficient `N + 1` of every state. The order is a constant, so every
            /// convolution is a loop of known length (unrolled by the compiler). Beyond the
            /// storage's capacity it does nothing.
            #[inline]
            pub fn order<const N: usize>(k: &Constants, s: &mut #storage) {
                let _ = k;
                #body
            }

            /// The last order `N` of an expansion: coefficient `N` of the observed series and
            /// of what they are computed from only (the states' polynomials, of degree `N`, are
            /// complete after order `N − 1`).
            #[inline]
            pub fn last<const N: usize>(k: &Constants, s: &mut #storage) {
                let _ = k;
                #last
            }
        }
    };
    EmittedSystem {
        tokens,
        constants,
        order0: c0,
        per_order: (fixed, per_n),
        series: program.ops.len(),
    }
}
