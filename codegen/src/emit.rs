//! Emission: each formula becomes a pure function of small `Copy` input structs returning a small
//! `Copy` struct, written with `quote` as straight-line code (CSE bindings `t0, t1, …`),
//! precedence-aware so the output reads like hand-written arithmetic. Transcendental calls go
//! through the runtime's math shim (`m::sqrt`, …). Operation counts are taken while emitting, so
//! they match the code exactly.
//!
//! A formula's inputs are the structs ([`Group`]s of the declaration table) of the symbols its
//! outputs use, in table order; a symbol declared in no group fails the build naming the symbol
//! and the formula.

use std::collections::BTreeSet;

use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;

use crate::expr::{ExprId, Graph, Node, Symbol};
use crate::ir::{Formula, Group};
use crate::optimize::{OpCounts, Plan, plan};

/// Emitted tokens of one formula, with its operation counts.
pub struct Emitted {
    /// The struct and the function.
    pub tokens: TokenStream,
    /// Counts if evaluated as expression trees (before CSE).
    pub before: OpCounts,
    /// Counts of the emitted code (after CSE).
    pub after: OpCounts,
    /// The declared structs the function takes or returns (to be emitted once).
    pub groups: Vec<&'static Group>,
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
    /// Local name of each input symbol (its struct field).
    locals: std::collections::HashMap<Symbol, &'static str>,
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
                let i = ident(self.locals.get(&s).copied().unwrap_or("undeclared"));
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

    /// |c|·M for a product c·M the plan writes through its magnitude M (`Plan::negated`), when
    /// M is bound: the term subtracted in a sum.
    fn negated_magnitude(&mut self, t: ExprId) -> Option<TokenStream> {
        let &(c, m) = self.plan.negated.get(&t)?;
        let k = *self.plan.temp_index.get(&m)?;
        let tm = temp(k);
        if c == -1.0 {
            Some(quote!(#tm))
        } else {
            self.counts.mul += 1;
            let lit = Self::literal(-c).0;
            Some(quote!(#lit * #tm))
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
                if let Some(written) = self.negated_magnitude(t) {
                    written
                } else {
                    match self.g.node(t).clone() {
                        Node::Const(bits) => Self::literal(-f64::from_bits(bits)).0,
                        Node::Mul(fs) => self.product(&fs, true).0,
                        _ => unreachable!("negative terms are constants or products"),
                    }
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

/// The input symbols `outputs` depend on.
/// The input symbols the expressions `outputs` depend on.
pub fn free_symbols(g: &Graph, outputs: &[ExprId]) -> BTreeSet<Symbol> {
    let mut stack = outputs.to_vec();
    let mut seen = std::collections::HashSet::new();
    let mut out = BTreeSet::new();
    while let Some(e) = stack.pop() {
        if !seen.insert(e) {
            continue;
        }
        if let Node::Input(s) = g.node(e) {
            out.insert(*s);
        }
        stack.extend(g.children(e));
    }
    out
}

/// The struct of a declared group (emitted once per file).
pub fn emit_group(group: &Group) -> TokenStream {
    if group.external.is_some() {
        return TokenStream::new();
    }
    let ty = ident(group.ty);
    let doc = doc_attrs(&[group.doc.to_owned()]);
    let mut decls = TokenStream::new();
    for &(_, field, meaning) in group.fields {
        let name = ident(field);
        let d = format!(" {}", meaning.replace('[', "\\[").replace(']', "\\]"));
        decls.extend(quote!(#[doc = #d] pub #name: f64,));
    }
    quote! {
        #doc
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        pub struct #ty { #decls }
    }
}

/// The type of a group in signatures: its declared struct, or the runtime's own path.
fn type_path(group: &Group) -> TokenStream {
    match group.external {
        Some(path) => path
            .parse()
            .expect("an external group's path is a Rust path"),
        None => {
            let t = ident(group.ty);
            quote!(#t)
        }
    }
}

/// Emit one formula as a function (and its output struct unless that is a declared group).
/// `groups` is the declaration table the formula's symbols are resolved in.
///
/// # Panics
/// When an output uses a symbol that belongs to no group (undeclared, or derivation-internal),
/// when two inputs would share a local name, or when a declared output struct's fields differ
/// from the formula's outputs: the message names the formula and the symbol.
pub fn emit_formula(g: &Graph, f: &Formula, groups: &'static [Group]) -> Emitted {
    let outputs: Vec<ExprId> = f.outputs.iter().map(|o| o.expr).collect();
    let plan = plan(g, &outputs);
    // Resolve every input symbol to (group index, field).
    let mut used: Vec<(usize, usize, Symbol)> = Vec::new();
    for s in free_symbols(g, &outputs) {
        let name = g.symbol_name(s);
        let slot = groups.iter().enumerate().find_map(|(gi, grp)| {
            grp.fields
                .iter()
                .position(|fl| fl.0 == name)
                .map(|fi| (gi, fi))
        });
        let Some((gi, fi)) = slot else {
            panic!(
                "formula `{}` uses the symbol `{name}`, which is declared in no input struct: declare it once in codegen/src/model/symbols.rs",
                f.name
            );
        };
        used.push((gi, fi, s));
    }
    used.sort();
    let mut locals = std::collections::HashMap::new();
    let mut seen_local = std::collections::HashMap::new();
    for &(gi, fi, s) in &used {
        let field = groups[gi].fields[fi].1;
        if let Some(other) = seen_local.insert(field, g.symbol_name(s)) {
            panic!(
                "formula `{}` takes `{other}` and `{}` which share the local name `{field}`",
                f.name,
                g.symbol_name(s)
            );
        }
        locals.insert(s, field);
    }
    let mut em = Emitter {
        g,
        plan: &plan,
        counts: OpCounts::default(),
        locals,
    };
    let mut lets = TokenStream::new();
    for &(gi, fi, _) in &used {
        let arg = ident(groups[gi].arg);
        let field = ident(groups[gi].fields[fi].1);
        lets.extend(quote!(let #field = #arg.#field;));
    }
    for (k, &id) in plan.bindings.iter().enumerate() {
        let (e, _) = em.inline(id);
        let t = temp(k);
        lets.extend(quote!(let #t = #e;));
    }
    let ty = ident(&f.output_type);
    let declared = groups.iter().find(|grp| grp.ty == f.output_type);
    if let Some(grp) = declared {
        let names: Vec<&str> = f.outputs.iter().map(|o| o.name.as_str()).collect();
        let fields: Vec<&str> = grp.fields.iter().map(|fl| fl.1).collect();
        assert!(
            names == fields,
            "formula `{}` returns the declared struct `{}` but its outputs {names:?} differ from the struct's fields {fields:?}",
            f.name,
            grp.ty
        );
    }
    let mut fields = TokenStream::new();
    let mut decls = TokenStream::new();
    for o in &f.outputs {
        let name = ident(&o.name);
        let (e, _) = em.reference(o.expr);
        fields.extend(quote!(#name: #e,));
        // Brackets in a field's meaning (Kl[0][1]) are text, not intra-doc links.
        let doc = format!(" {}", o.doc.replace('[', "\\[").replace(']', "\\]"));
        decls.extend(quote!(#[doc = #doc] pub #name: f64,));
    }
    let mut arg_groups: Vec<usize> = used.iter().map(|u| u.0).collect();
    arg_groups.dedup();
    let params: Vec<TokenStream> = arg_groups
        .iter()
        .map(|&gi| {
            let a = ident(groups[gi].arg);
            let t = type_path(&groups[gi]);
            quote!(#a: &#t)
        })
        .collect();
    let hidden = if f.test_only {
        quote!(#[doc(hidden)])
    } else {
        TokenStream::new()
    };
    let struct_tokens = if declared.is_some() {
        TokenStream::new()
    } else {
        let struct_doc = doc_attrs(&[format!("Outputs of [`{}`].", f.name)]);
        quote! {
            #struct_doc
            #hidden
            #[derive(Clone, Copy, Debug, PartialEq)]
            pub struct #ty { #decls }
        }
    };
    let name = ident(&f.name);
    let mut doc_lines = vec![
        f.summary.clone(),
        String::new(),
        format!("Source: {}.", f.source),
        format!("Derivation: {}", f.derivation),
    ];
    if f.test_only {
        doc_lines.push(
            "Test-only: checks the derivation against the paper's form; the runtime does not use it."
                .to_owned(),
        );
    }
    let fn_doc = doc_attrs(&doc_lines);
    let tokens = quote! {
        #struct_tokens

        #fn_doc
        #hidden
        #[inline]
        #[must_use]
        pub fn #name(#(#params),*) -> #ty {
            #lets
            #ty { #fields }
        }
    };
    let mut used_groups: Vec<&'static Group> = arg_groups.iter().map(|&gi| &groups[gi]).collect();
    if let Some(grp) = declared {
        used_groups.push(grp);
    }
    Emitted {
        tokens,
        before: plan.before,
        after: em.counts,
        groups: used_groups,
    }
}
