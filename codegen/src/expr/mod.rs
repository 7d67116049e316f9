//! The hash-consed expression DAG.
//!
//! Every node is interned: building the same expression twice returns the same [`ExprId`], so
//! common sub-expressions are shared by construction and CSE only has to decide which shared
//! nodes get a name. Constructors simplify as they build (see `simplify`):
//! constant folding, neutral and absorbing elements, flattening, like-term and like-factor
//! collection. Sums and products are n-ary with their operands sorted by id, so equal sums are
//! equal nodes.

mod eval;
mod simplify;

use std::collections::HashMap;

pub use eval::Env;

/// Handle of an interned node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ExprId(pub(crate) u32);

/// Handle of a named input symbol.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Symbol(pub(crate) u32);

/// Elementary functions of one argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Func {
    /// Square root.
    Sqrt,
    /// Exponential.
    Exp,
    /// Sine.
    Sin,
    /// Cosine.
    Cos,
}

impl Func {
    /// The function's name in the runtime's math shim.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sqrt => "sqrt",
            Func::Exp => "exp",
            Func::Sin => "sin",
            Func::Cos => "cos",
        }
    }

    pub(crate) fn apply(self, x: f64) -> f64 {
        match self {
            Func::Sqrt => x.sqrt(),
            Func::Exp => x.exp(),
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
        }
    }
}

/// One node of the DAG.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A constant, stored as the bits of an `f64` (−0 normalised to +0).
    Const(u64),
    /// A named input.
    Input(Symbol),
    /// n-ary sum, n ≥ 2, operands sorted, at most one constant (first, by construction).
    Add(Vec<ExprId>),
    /// n-ary product, n ≥ 2, operands sorted, at most one constant.
    Mul(Vec<ExprId>),
    /// Integer power, exponent ∉ {0, 1}.
    Pow(ExprId, i32),
    /// An elementary function.
    Call(Func, ExprId),
}

/// The expression graph: interned nodes and the input symbols' names.
#[derive(Default)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, ExprId>,
    symbols: Vec<String>,
    symbol_index: HashMap<String, Symbol>,
}

impl Graph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// The node behind `id`.
    pub fn node(&self, id: ExprId) -> &Node {
        &self.nodes[id.0 as usize]
    }

    /// Number of interned nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the graph has no nodes.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// A symbol's name.
    pub fn symbol_name(&self, s: Symbol) -> &str {
        &self.symbols[s.0 as usize]
    }

    /// The symbol named `name` (created on first use).
    pub fn symbol(&mut self, name: &str) -> Symbol {
        if let Some(&s) = self.symbol_index.get(name) {
            return s;
        }
        let s = Symbol(self.symbols.len() as u32);
        self.symbols.push(name.to_owned());
        self.symbol_index.insert(name.to_owned(), s);
        s
    }

    /// The input expression for the symbol named `name`.
    pub fn input(&mut self, name: &str) -> ExprId {
        let s = self.symbol(name);
        self.intern(Node::Input(s))
    }

    /// The input expression for symbol `s`.
    pub fn input_of(&mut self, s: Symbol) -> ExprId {
        self.intern(Node::Input(s))
    }

    /// The symbol of an input expression.
    pub fn as_symbol(&self, id: ExprId) -> Option<Symbol> {
        match self.node(id) {
            Node::Input(s) => Some(*s),
            _ => None,
        }
    }

    /// A constant.
    pub fn constant(&mut self, value: f64) -> ExprId {
        let v = if value == 0.0 { 0.0 } else { value };
        self.intern(Node::Const(v.to_bits()))
    }

    /// The constant value of `id`, if it is a constant.
    pub fn as_const(&self, id: ExprId) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(*bits)),
            _ => None,
        }
    }

    /// Whether `id` is the constant `value`.
    pub fn is_const(&self, id: ExprId, value: f64) -> bool {
        self.as_const(id) == Some(value)
    }

    /// The id of `node` if it is interned (without interning it).
    pub fn lookup(&self, node: &Node) -> Option<ExprId> {
        self.index.get(node).copied()
    }

    pub(crate) fn intern(&mut self, node: Node) -> ExprId {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = ExprId(self.nodes.len() as u32);
        self.nodes.push(node.clone());
        self.index.insert(node, id);
        id
    }

    /// `a + b`.
    pub fn add(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.sum(&[a, b])
    }

    /// `a − b`.
    pub fn sub(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let nb = self.neg(b);
        self.sum(&[a, nb])
    }

    /// `−a`.
    pub fn neg(&mut self, a: ExprId) -> ExprId {
        let m1 = self.constant(-1.0);
        self.product(&[m1, a])
    }

    /// `a · b`.
    pub fn mul(&mut self, a: ExprId, b: ExprId) -> ExprId {
        self.product(&[a, b])
    }

    /// `a / b`.
    pub fn div(&mut self, a: ExprId, b: ExprId) -> ExprId {
        let inv = self.powi(b, -1);
        self.product(&[a, inv])
    }

    /// `c · a` for a constant `c`.
    pub fn scale(&mut self, c: f64, a: ExprId) -> ExprId {
        let k = self.constant(c);
        self.product(&[k, a])
    }

    /// `sqrt(a)`.
    pub fn sqrt(&mut self, a: ExprId) -> ExprId {
        self.call(Func::Sqrt, a)
    }

    /// `exp(a)`.
    pub fn exp(&mut self, a: ExprId) -> ExprId {
        self.call(Func::Exp, a)
    }

    /// `sin(a)`.
    pub fn sin(&mut self, a: ExprId) -> ExprId {
        self.call(Func::Sin, a)
    }

    /// `cos(a)`.
    pub fn cos(&mut self, a: ExprId) -> ExprId {
        self.call(Func::Cos, a)
    }

    /// Replace inputs by expressions (`map` from symbol to replacement) throughout `id`.
    pub fn substitute(&mut self, id: ExprId, map: &HashMap<Symbol, ExprId>) -> ExprId {
        let mut memo = HashMap::new();
        self.substitute_memo(id, map, &mut memo)
    }

    fn substitute_memo(
        &mut self,
        id: ExprId,
        map: &HashMap<Symbol, ExprId>,
        memo: &mut HashMap<ExprId, ExprId>,
    ) -> ExprId {
        if let Some(&r) = memo.get(&id) {
            return r;
        }
        let r = match self.node(id).clone() {
            Node::Const(_) => id,
            Node::Input(s) => map.get(&s).copied().unwrap_or(id),
            Node::Add(ts) => {
                let ts: Vec<_> = ts
                    .iter()
                    .map(|&t| self.substitute_memo(t, map, memo))
                    .collect();
                self.sum(&ts)
            }
            Node::Mul(fs) => {
                let fs: Vec<_> = fs
                    .iter()
                    .map(|&f| self.substitute_memo(f, map, memo))
                    .collect();
                self.product(&fs)
            }
            Node::Pow(b, n) => {
                let b = self.substitute_memo(b, map, memo);
                self.powi(b, n)
            }
            Node::Call(f, a) => {
                let a = self.substitute_memo(a, map, memo);
                self.call(f, a)
            }
        };
        memo.insert(id, r);
        r
    }

    /// The direct operands of a node.
    pub fn children(&self, id: ExprId) -> Vec<ExprId> {
        match self.node(id) {
            Node::Const(_) | Node::Input(_) => vec![],
            Node::Add(v) | Node::Mul(v) => v.clone(),
            Node::Pow(b, _) => vec![*b],
            Node::Call(_, a) => vec![*a],
        }
    }

    /// Whether the input symbol `s` occurs in `id`.
    pub fn depends_on(&self, id: ExprId, s: Symbol) -> bool {
        let mut stack = vec![id];
        let mut seen = std::collections::HashSet::new();
        while let Some(e) = stack.pop() {
            if !seen.insert(e) {
                continue;
            }
            if matches!(self.node(e), Node::Input(t) if *t == s) {
                return true;
            }
            stack.extend(self.children(e));
        }
        false
    }
}
