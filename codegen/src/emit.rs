//! Emission: each formula becomes a pure `f64` function returning a small `Copy` struct, written
//! with `quote` as straight-line code (CSE bindings `t0, t1, …`), precedence-aware so the output
//! reads like hand-written arithmetic. Transcendental calls go through the runtime's math shim
//! (`m::sqrt`, …). Operation counts are taken while emitting, so they match the code exactly.

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use crate::expr::{ExprId, Graph, Node, Symbol};
use crate::optimize::{OpCounts, Plan, plan};

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
    /// Where the formula is stated (`model.md` section).
    pub source: String,
    /// How the generator derived it.
    pub derivation: String,
    /// Input symbols, in signature order.
    pub inputs: Vec<Symbol>,
    /// Output struct name.
    pub output_type: String,
    /// Outputs, in struct order.
    pub outputs: Vec<Output>,
}

/// Emitted tokens of one formula, with its operation counts.
pub struct Emitted {
    /// The struct and the function.
    pub tokens: TokenStream,
    /// Counts if evaluated as expression trees (before CSE).
    pub before: OpCounts,
    /// Counts of the emitted code (after CSE).
    pub after: OpCounts,
}

#[derive(Clone, Copy, PartialEq, PartialOrd)]
enum Prec {
    Sum,
    Product,
    Unary,
    Atom,
}

struct Emitter<'a> {
    g: &'a Graph,
    plan: &'a Plan,
    counts: OpCounts,
}

fn ident(name: &str) -> Ident {
    Ident::new(name, Span::call_site())
}

fn temp(k: usize) -> Ident {
    ident(&format!("t{k}"))
}

impl Emitter<'_> {
    /// The expression `id` as a reference: a binding's name, an input or a constant, or the
    /// expression itself inlined.
    fn reference(&mut self, id: ExprId) -> (TokenStream, Prec) {
        if let Some(&k) = self.plan.temp_index.get(&id) {
            let t = temp(k);
            return (quote!(#t), Prec::Atom);
        }
        self.inline(id)
    }

    fn wrapped(&mut self, id: ExprId, min: Prec) -> TokenStream {
        let (t, p) = self.reference(id);
        if p < min { quote!((#t)) } else { t }
    }

    fn literal(v: f64) -> (TokenStream, Prec) {
        let lit = Literal::f64_unsuffixed(v.abs());
        if v < 0.0 {
            (quote!(-#lit), Prec::Unary)
        } else {
            (quote!(#lit), Prec::Atom)
        }
    }

    /// The node itself written out (its operands by reference).
    fn inline(&mut self, id: ExprId) -> (TokenStream, Prec) {
        match self.g.node(id).clone() {
            Node::Const(bits) => Self::literal(f64::from_bits(bits)),
            Node::Input(s) => {
                let i = ident(self.g.symbol_name(s));
                (quote!(#i), Prec::Atom)
            }
            Node::Add(ts) => self.sum(&ts),
            Node::Mul(fs) => self.product(&fs, false),
            Node::Pow(b, n) => {
                let base = self.wrapped(b, Prec::Unary);
                let k = n.unsigned_abs() as usize;
                self.counts.mul += (k - 1) as u64;
                let mut out = base.clone();
                for _ in 1..k {
                    out.extend(quote!(* #base));
                }
                if n < 0 {
                    self.counts.div += 1;
                    let one = Self::literal(1.0).0;
                    if k > 1 {
                        (quote!(#one / (#out)), Prec::Product)
                    } else {
                        (quote!(#one / #out), Prec::Product)
                    }
                } else if k > 1 {
                    (out, Prec::Product)
                } else {
                    (out, Prec::Atom)
                }
            }
            Node::Call(f, a) => {
                let (arg, _) = self.reference(a);
                let name = ident(f.name());
                if f == crate::expr::Func::Sqrt {
                    self.counts.sqrt += 1;
                } else {
                    self.counts.transcendental += 1;
                }
                (quote!(m::#name(#arg)), Prec::Atom)
            }
        }
    }

    /// A term's sign and magnitude: `c·rest` with c < 0 is written as a subtraction of `|c|·rest`.
    fn negative_term(&self, t: ExprId) -> bool {
        if self.plan.temp_index.contains_key(&t) {
            return false;
        }
        match self.g.node(t) {
            Node::Const(bits) => f64::from_bits(*bits) < 0.0,
            Node::Mul(fs) => fs
                .iter()
                .any(|&f| self.g.as_const(f).is_some_and(|c| c < 0.0)),
            _ => false,
        }
    }

    fn sum(&mut self, ts: &[ExprId]) -> (TokenStream, Prec) {
        // Positive terms first, so the sum reads `a + b - c`.
        let mut ordered: Vec<(ExprId, bool)> =
            ts.iter().map(|&t| (t, self.negative_term(t))).collect();
        ordered.sort_by_key(|&(_, neg)| neg);
        let mut out = TokenStream::new();
        for (k, &(t, neg)) in ordered.iter().enumerate() {
            let term = if neg {
                match self.g.node(t).clone() {
                    Node::Const(bits) => Self::literal(-f64::from_bits(bits)).0,
                    Node::Mul(fs) => self.product(&fs, true).0,
                    _ => unreachable!("negative terms are constants or products"),
                }
            } else {
                self.wrapped(t, Prec::Sum)
            };
            if k > 0 {
                self.counts.add += 1;
                out.extend(if neg {
                    quote!(- #term)
                } else {
                    quote!(+ #term)
                });
            } else if neg {
                out.extend(quote!(-(#term)));
            } else {
                out.extend(term);
            }
        }
        (out, Prec::Sum)
    }

    /// A product written as `coefficient * a * b / (c * d)`; `negate` flips the coefficient's sign.
    fn product(&mut self, fs: &[ExprId], negate: bool) -> (TokenStream, Prec) {
        let mut coef = if negate { -1.0 } else { 1.0 };
        let mut num: Vec<TokenStream> = Vec::new();
        let mut den: Vec<TokenStream> = Vec::new();
        for &f in fs {
            if let Some(c) = self.g.as_const(f) {
                coef *= c;
                continue;
            }
            match self.g.node(f).clone() {
                Node::Pow(b, n) if !self.plan.temp_index.contains_key(&f) => {
                    let base = self.wrapped(b, Prec::Unary);
                    let list = if n < 0 { &mut den } else { &mut num };
                    for _ in 0..n.unsigned_abs() {
                        list.push(base.clone());
                    }
                }
                _ => {
                    let t = self.wrapped(f, Prec::Product);
                    num.push(t);
                }
            }
        }
        if coef.abs() != 1.0 {
            num.insert(0, Self::literal(coef.abs()).0);
        }
        if num.is_empty() {
            num.push(Self::literal(1.0).0);
        }
        self.counts.mul += (num.len() - 1) as u64 + den.len().saturating_sub(1) as u64;
        let mut out = TokenStream::new();
        for (k, t) in num.iter().enumerate() {
            if k > 0 {
                out.extend(quote!(*));
            }
            out.extend(t.clone());
        }
        if !den.is_empty() {
            self.counts.div += 1;
            let mut d = TokenStream::new();
            for (k, t) in den.iter().enumerate() {
                if k > 0 {
                    d.extend(quote!(*));
                }
                d.extend(t.clone());
            }
            if den.len() > 1 {
                out.extend(quote!(/ (#d)));
            } else {
                out.extend(quote!(/ #d));
            }
        }
        if coef < 0.0 {
            (quote!(-#out), Prec::Unary)
        } else {
            (out, Prec::Product)
        }
    }
}

fn doc_attrs(lines: &[String]) -> TokenStream {
    let mut out = TokenStream::new();
    for l in lines {
        let text = format!(" {l}");
        out.extend(quote!(#[doc = #text]));
    }
    out
}

/// Emit one formula as a struct and a function.
pub fn emit_formula(g: &Graph, f: &Formula) -> Emitted {
    let outputs: Vec<ExprId> = f.outputs.iter().map(|o| o.expr).collect();
    let plan = plan(g, &outputs);
    for &s in &f.inputs {
        let used = outputs.iter().any(|&o| g.depends_on(o, s));
        assert!(
            used,
            "input `{}` of `{}` is unused",
            g.symbol_name(s),
            f.name
        );
    }
    let mut em = Emitter {
        g,
        plan: &plan,
        counts: OpCounts::default(),
    };
    let mut lets = TokenStream::new();
    for (k, &id) in plan.bindings.iter().enumerate() {
        let (e, _) = em.inline(id);
        let t = temp(k);
        lets.extend(quote!(let #t = #e;));
    }
    let ty = ident(&f.output_type);
    let mut fields = TokenStream::new();
    let mut decls = TokenStream::new();
    for o in &f.outputs {
        let name = ident(&o.name);
        let (e, _) = em.reference(o.expr);
        fields.extend(quote!(#name: #e,));
        let doc = format!(" {}", o.doc);
        decls.extend(quote!(#[doc = #doc] pub #name: f64,));
    }
    let params: Vec<TokenStream> = f
        .inputs
        .iter()
        .map(|&s| {
            let i = ident(g.symbol_name(s));
            quote!(#i: f64)
        })
        .collect();
    let name = ident(&f.name);
    let struct_doc = doc_attrs(&[format!("Outputs of [`{}`].", f.name)]);
    let fn_doc = doc_attrs(&[
        f.summary.clone(),
        String::new(),
        format!("Source: {}.", f.source),
        format!("Derivation: {}", f.derivation),
    ]);
    let tokens = quote! {
        #struct_doc
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct #ty { #decls }

        #fn_doc
        #[inline]
        #[must_use]
        pub fn #name(#(#params),*) -> #ty {
            #lets
            #ty { #fields }
        }
    };
    Emitted {
        tokens,
        before: plan.before,
        after: em.counts,
    }
}
