//! Phenomena: checking the scene's named shader graphs once where they are declared —
//! duplicate names, cycles of `Graph` calls (reported with the whole chain), interface
//! parameters and their types (fixed by the defaults), and the body. Calls are expanded by
//! [`super`].

use std::collections::HashMap;

use super::size::Size;
use super::textures::Textures;
use super::{At, Compiler, Ty};
use crate::memory_budget::Budget;
use crate::scene::diagnostics::Sources;
use crate::scene::nodes_desc::{InputDesc, NodeDesc, PhenomenonDesc};
use crate::scene::validate::{Item, Merged};
use crate::shading::texture::Program;

/// What checking a phenomenon found.
#[derive(Debug, Clone)]
pub(super) struct Checked {
    /// Interface parameters and their types, by name.
    pub(super) params: Vec<(String, Ty)>,
    /// Type of the output; `None` when the phenomenon has errors.
    pub(super) output: Option<Ty>,
}

/// The scene's phenomena, checked.
pub struct Phenomena<'a> {
    /// The declarations, in load order.
    pub(super) items: &'a [Item<'a, PhenomenonDesc>],
    /// Index of each name (first declaration).
    pub(super) by_name: HashMap<&'a str, usize>,
    /// What checking found, per phenomenon (`None`: not checked yet).
    pub(super) checked: Vec<Option<Checked>>,
    /// Phenomena on a cycle (never expanded).
    pub(super) cyclic: Vec<bool>,
    /// Phenomena whose call chains nest deeper than the limit (never expanded; see
    /// [`super::nodes_depth`]).
    pub(super) too_deep: Vec<bool>,
    /// Image textures read so far, counted against the run's memory budget.
    pub(super) textures: Textures,
    /// Nodes of the compilations done so far (see [`super::size`]).
    pub(super) expanded: usize,
    /// Whether the scene's limit on expanded nodes was reported.
    pub(super) scene_size_reported: bool,
}

impl Phenomena<'_> {
    /// Every image texture the scene's graphs decoded, in the order read.
    pub fn decoded_textures(&self) -> &[super::DecodedTexture] {
        self.textures.listed()
    }
}

/// Checks every phenomenon (duplicate names, cycles, bodies, defaults); the image textures
/// they and the materials read are counted against `budget`.
pub fn check_phenomena<'a>(src: &mut Sources, m: &'a Merged<'a>, budget: &Budget) -> Phenomena<'a> {
    let mut by_name = HashMap::new();
    for (i, it) in m.phenomena.iter().enumerate() {
        if let Some(&first) = by_name.get(it.desc.name.as_str()) {
            let first: &Item<'_, PhenomenonDesc> = &m.phenomena[first];
            let help = format!(
                "first defined at {}",
                src.where_is(first.file, &first.at(".name"))
            );
            src.error(
                it.file,
                &it.at(".name"),
                format!("phenomenon \"{}\" is defined twice", it.desc.name),
                Some(help),
            );
        } else {
            by_name.insert(it.desc.name.as_str(), i);
        }
    }
    let n = m.phenomena.len();
    let mut ph = Phenomena {
        items: &m.phenomena,
        by_name,
        checked: vec![None; n],
        cyclic: vec![false; n],
        too_deep: vec![false; n],
        textures: Textures::new(budget.clone()),
        expanded: 0,
        scene_size_reported: false,
    };
    find_cycles(src, &mut ph);
    super::depth::check_depth(src, &mut ph);
    for i in 0..n {
        ensure_checked(src, &mut ph, i);
    }
    ph
}

/// Reports every phenomenon that reaches itself through `Graph` calls.
fn find_cycles(src: &mut Sources, ph: &mut Phenomena<'_>) {
    let n = ph.items.len();
    // Calls of each phenomenon: (callee, path of the call).
    let calls: Vec<Vec<(usize, String)>> = ph
        .items
        .iter()
        .map(|it| {
            let mut out = Vec::new();
            collect_calls(&it.desc.output, &it.at(".output"), &ph.by_name, &mut out);
            for (k, v) in &it.desc.params {
                collect_calls(v, &it.at(&format!(".params.{k}")), &ph.by_name, &mut out);
            }
            out
        })
        .collect();
    for start in 0..n {
        // Depth-first search for a path from `start` back to itself.
        let mut seen = vec![false; n];
        let mut stack = vec![(start, 0usize)];
        let mut chain = vec![start];
        while let Some(&mut (node, ref mut next)) = stack.last_mut() {
            if *next >= calls[node].len() {
                stack.pop();
                chain.pop();
                continue;
            }
            let (callee, _) = calls[node][*next];
            *next += 1;
            if callee == start {
                ph.cyclic[start] = true;
                let names: Vec<&str> = chain
                    .iter()
                    .chain(std::iter::once(&start))
                    .map(|&i| ph.items[i].desc.name.as_str())
                    .collect();
                let it = &ph.items[start];
                let (_, path) = &calls[start][stack[0].1 - 1];
                src.error(
                    it.file,
                    path,
                    format!(
                        "phenomenon \"{}\" uses itself: {}",
                        it.desc.name,
                        names.join(" → ")
                    ),
                    Some("a phenomenon cannot call itself, directly or through others".into()),
                );
                break;
            }
            if !seen[callee] {
                seen[callee] = true;
                stack.push((callee, 0));
                chain.push(callee);
            }
        }
    }
}

pub(super) fn collect_calls(
    d: &InputDesc,
    path: &str,
    by_name: &HashMap<&str, usize>,
    out: &mut Vec<(usize, String)>,
) {
    let InputDesc::Node(n) = d else { return };
    let mut sub = |d: &InputDesc, p: String| collect_calls(d, &p, by_name, out);
    match &**n {
        NodeDesc::Graph(name, args) => {
            for (k, v) in args {
                sub(v, format!("{path}.Graph[1].{k}"));
            }
            if let Some(&i) = by_name.get(name.as_str()) {
                out.push((i, path.to_string()));
            }
        }
        other => {
            for_each_input(other, |field, d| sub(d, format!("{path}{field}")));
        }
    }
}

/// Calls `f` with the path suffix and description of every input of a node (not `Graph`).
fn for_each_input(n: &NodeDesc, mut f: impl FnMut(String, &InputDesc)) {
    let mut named = |variant: &str, fields: &[(&str, &InputDesc)]| {
        for (k, v) in fields {
            f(format!(".{variant}.{k}"), v);
        }
    };
    match n {
        NodeDesc::Checker { uv, scale, a, b } => named(
            "Checker",
            &[("uv", uv), ("scale", scale), ("a", a), ("b", b)],
        ),
        NodeDesc::Disk {
            uv,
            radius,
            fuzz,
            inside,
            outside,
            ..
        } => named(
            "Disk",
            &[
                ("uv", uv),
                ("radius", radius),
                ("fuzz", fuzz),
                ("inside", inside),
                ("outside", outside),
            ],
        ),
        NodeDesc::Steps { uv, steps, fuzz } => {
            named("Steps", &[("uv", uv), ("steps", steps), ("fuzz", fuzz)])
        }
        NodeDesc::Repeat { uv, scale } => named("Repeat", &[("uv", uv), ("scale", scale)]),
        NodeDesc::Noise { p, .. } => named("Noise", &[("p", p)]),
        NodeDesc::Fbm { p, .. } => named("Fbm", &[("p", p)]),
        NodeDesc::Turbulence { p, .. } => named("Turbulence", &[("p", p)]),
        NodeDesc::Image { uv, .. } => named("Image", &[("uv", uv)]),
        NodeDesc::Alpha { uv, .. } => named("Alpha", &[("uv", uv)]),
        NodeDesc::Mix { a, b, t } => named("Mix", &[("a", a), ("b", b), ("t", t)]),
        NodeDesc::Smoothstep { edge0, edge1, x } => named(
            "Smoothstep",
            &[("edge0", edge0), ("edge1", edge1), ("x", x)],
        ),
        NodeDesc::Convert { input, .. } => named("Convert", &[("input", input)]),
        NodeDesc::Add(a, b) | NodeDesc::Sub(a, b) | NodeDesc::Mul(a, b) => {
            let v = variant_name(n);
            f(format!(".{v}[0]"), a);
            f(format!(".{v}[1]"), b);
        }
        NodeDesc::Channel(a, _) => f(".Channel[0]".into(), a),
        NodeDesc::Luminance(a) => f(".Luminance[0]".into(), a),
        NodeDesc::Combine(a, b, c) => {
            f(".Combine[0]".into(), a);
            f(".Combine[1]".into(), b);
            f(".Combine[2]".into(), c);
        }
        NodeDesc::Uv
        | NodeDesc::Position
        | NodeDesc::Normal
        | NodeDesc::VertexColor
        | NodeDesc::Graph(..)
        | NodeDesc::Param(_) => {}
    }
}

/// `Add`, `Sub` or `Mul`: the name of an arithmetic node.
pub(super) fn variant_name(n: &NodeDesc) -> &'static str {
    match n {
        NodeDesc::Add(..) => "Add",
        NodeDesc::Sub(..) => "Sub",
        _ => "Mul",
    }
}

/// Checks phenomenon `i` (once), after the phenomena it calls.
pub(super) fn ensure_checked(src: &mut Sources, ph: &mut Phenomena<'_>, i: usize) {
    if ph.checked[i].is_some() {
        return;
    }
    if ph.too_deep[i] {
        // Reported by `nodes_depth`; checking the body would recurse down the whole chain.
        ph.checked[i] = Some(Checked {
            params: Vec::new(),
            output: None,
        });
        return;
    }
    // Mark first: acyclic calls cannot come back here.
    ph.checked[i] = Some(Checked {
        params: Vec::new(),
        output: None,
    });
    let item = &ph.items[i];
    let (file, desc) = (item.file, item.desc);
    let base = item.path.clone();
    let mut c = Compiler {
        src,
        ph,
        prog: Program::default(),
        stack: vec![i],
        report: true,
        size: Size::Within,
    };
    let mut env = Vec::new();
    let mut params = Vec::new();
    let mut ok = true;
    for (k, v) in &desc.params {
        let path = format!("{base}.params.{k}");
        match c.input(At { file, path: &path }, v, &[]) {
            Some((reg, ty)) => {
                env.push((k.clone(), ty, reg));
                params.push((k.clone(), ty));
            }
            None => ok = false,
        }
    }
    // The interface is known before the body: calls back into this phenomenon (only
    // possible on a cycle, which is reported already) check their arguments against it.
    c.ph.checked[i] = Some(Checked {
        params: params.clone(),
        output: None,
    });
    let path = format!("{base}.output");
    let out = c.input(At { file, path: &path }, &desc.output, &env);
    c.count_expanded();
    let cyclic = c.ph.cyclic[i];
    c.ph.checked[i] = Some(Checked {
        params,
        output: out.filter(|_| ok && !cyclic).map(|(_, t)| t),
    });
}
