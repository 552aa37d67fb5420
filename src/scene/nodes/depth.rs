//! How deep phenomenon calls nest (issue 18, family 3): every call is expanded inline by a
//! recursive compiler, so a chain of thousands of phenomena each calling the next would
//! overflow the stack. Chains longer than [`MAX_PHENOMENON_DEPTH`] are refused where they
//! start, with the chain and the limit; their phenomena are never expanded.

use super::phenomena::{collect_calls, Phenomena};
use crate::scene::diagnostics::Sources;

/// The most phenomena a chain of `Graph` calls may pass through (the caller included).
pub const MAX_PHENOMENON_DEPTH: usize = 64;

/// Measures the longest call chain from every phenomenon (cycles are reported elsewhere and
/// not followed), marks those beyond the limit in `ph.too_deep`, and reports each chain once,
/// at the call that starts it in the outermost phenomenon.
pub(super) fn check_depth(src: &mut Sources, ph: &mut Phenomena<'_>) {
    let n = ph.items.len();
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
    // depth[i]: phenomena on the longest chain from i; next[i]: the call that continues it.
    let mut depth = vec![0usize; n];
    let mut next: Vec<Option<usize>> = vec![None; n];
    let mut state = vec![0u8; n]; // 0 new, 1 on the stack, 2 done
    for start in 0..n {
        if state[start] != 0 {
            continue;
        }
        let mut stack = vec![(start, 0usize)];
        state[start] = 1;
        while let Some(&mut (node, ref mut k)) = stack.last_mut() {
            if let Some(&(callee, _)) = calls[node].get(*k) {
                *k += 1;
                if state[callee] == 0 && !ph.cyclic[callee] {
                    state[callee] = 1;
                    stack.push((callee, 0));
                }
                continue;
            }
            let best = calls[node]
                .iter()
                .enumerate()
                .filter(|(_, (c, _))| state[*c] == 2)
                .max_by_key(|(j, (c, _))| (depth[*c], std::cmp::Reverse(*j)));
            depth[node] = 1 + best.map_or(0, |(_, (c, _))| depth[*c]);
            next[node] = best.map(|(j, _)| j);
            state[node] = 2;
            stack.pop();
        }
    }
    for (too_deep, &d) in ph.too_deep.iter_mut().zip(&depth) {
        *too_deep = d > MAX_PHENOMENON_DEPTH;
    }
    let called_by_too_deep: Vec<bool> = (0..n)
        .map(|c| (0..n).any(|i| ph.too_deep[i] && calls[i].iter().any(|(x, _)| *x == c)))
        .collect();
    for i in 0..n {
        if !ph.too_deep[i] || called_by_too_deep[i] {
            continue;
        }
        let mut chain = vec![i];
        let mut at = i;
        while let Some(j) = next[at] {
            at = calls[at][j].0;
            chain.push(at);
        }
        let name = |k: usize| ph.items[k].desc.name.as_str();
        let shown = if chain.len() > 4 {
            format!(
                "{} → {} → … → {}",
                name(chain[0]),
                name(chain[1]),
                name(chain[chain.len() - 1])
            )
        } else {
            chain
                .iter()
                .map(|&k| name(k))
                .collect::<Vec<_>>()
                .join(" → ")
        };
        let it = &ph.items[i];
        let path = next[i].map_or_else(|| it.at(".output"), |j| calls[i][j].1.clone());
        src.error(
            it.file,
            &path,
            format!(
                "phenomenon \"{}\" starts a chain of {} nested phenomenon calls ({shown}); the limit is {MAX_PHENOMENON_DEPTH}",
                it.desc.name,
                depth[i]
            ),
            Some("call fewer phenomena inside each other: inline some of them".into()),
        );
    }
}
