//! The house's import rules, checked on the source tree (the rules and their reasons are written
//! once, in `tests/architecture.toml`):
//! 1. no import circle between the source files of any crate of the workspace;
//! 2. the library's folders (`crates/flexrig/src/*/`) import one way, each only the folders the
//!    rules list for it.
//!
//! A file imports another when its code names an item through a path that resolves into that
//! file's module: a private `use crate::…`/`super::…`/`self::…` (braces expanded) or such a path
//! inline. Module declarations and re-exports (`pub use`, `pub(crate) use`) are a module's facade,
//! not its code's dependency, and are left out, as are test modules (`#[cfg(test)]`), `tests/`,
//! `benches/` and `examples/`. A failure names the files and the path that broke the rule.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The workspace's root (this package sits in `tests/`).
fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// A module's path from the crate root (`["safety", "map"]`; the root is empty).
type ModPath = Vec<String>;

/// One crate's modules (path → file) and its files' imports (file → files, with the path that
/// made each edge).
struct CrateGraph {
    modules: BTreeMap<ModPath, PathBuf>,
    edges: BTreeMap<PathBuf, BTreeMap<PathBuf, String>>,
}

/// The text the compiler reads as code: comments, string, byte-string and char literals
/// dropped (a string becomes `""`).
fn strip_literals(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let n = b.len();
    let mut out = String::with_capacity(n);
    let mut i = 0;
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    while i < n {
        let c = b[i];
        if c == '/' && i + 1 < n && b[i + 1] == '/' {
            while i < n && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && i + 1 < n && b[i + 1] == '*' {
            let mut depth = 1;
            i += 2;
            while i < n && depth > 0 {
                if b[i] == '/' && i + 1 < n && b[i + 1] == '*' {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && i + 1 < n && b[i + 1] == '/' {
                    depth -= 1;
                    i += 2;
                } else {
                    i += 1;
                }
            }
        } else if (c == 'r' || (c == 'b' && i + 1 < n && b[i + 1] == 'r'))
            && (i == 0 || !ident(b[i - 1]))
            && {
                let mut j = i + if c == 'b' { 2 } else { 1 };
                while j < n && b[j] == '#' {
                    j += 1;
                }
                j < n && b[j] == '"'
            }
        {
            // a raw string r#"…"#: ends at the quote followed by as many #
            let mut j = i + if c == 'b' { 2 } else { 1 };
            let mut hashes = 0;
            while b[j] == '#' {
                hashes += 1;
                j += 1;
            }
            j += 1;
            loop {
                if j >= n {
                    break;
                }
                if b[j] == '"' && (0..hashes).all(|k| j + 1 + k < n && b[j + 1 + k] == '#') {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            out.push_str("\"\"");
            i = j;
        } else if c == '"' {
            let mut j = i + 1;
            while j < n && b[j] != '"' {
                j += if b[j] == '\\' { 2 } else { 1 };
            }
            out.push_str("\"\"");
            i = j + 1;
        } else if c == '\'' {
            // a char literal ('x', '\n', '\u{..}'), not a lifetime ('a)
            let close = if i + 2 < n && b[i + 1] == '\\' {
                (i + 2..n.min(i + 12)).find(|&j| b[j] == '\'')
            } else if i + 2 < n && b[i + 2] == '\'' {
                Some(i + 2)
            } else {
                None
            };
            match close {
                Some(j) => {
                    out.push_str("' '");
                    i = j + 1;
                }
                None => {
                    out.push(c);
                    i += 1;
                }
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// `text` without its `#[cfg(test)]` inline modules.
fn strip_test_modules(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("#[cfg(test)]") {
        let after = &rest[at + "#[cfg(test)]".len()..];
        let t = after.trim_start();
        let t = t.strip_prefix("pub ").unwrap_or(t).trim_start();
        let inline_module =
            t.starts_with("mod ") && t.find(['{', ';']).is_some_and(|k| t.as_bytes()[k] == b'{');
        if !inline_module {
            out.push_str(&rest[..at + "#[cfg(test)]".len()]);
            rest = after;
            continue;
        }
        out.push_str(&rest[..at]);
        let open = after.find('{').unwrap();
        let mut depth = 0usize;
        let mut end = after.len();
        for (k, ch) in after[open..].char_indices() {
            match ch {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + k + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

/// The code of a source file as the rules read it.
fn code(file: &Path) -> String {
    let text = std::fs::read_to_string(file)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", file.display()));
    strip_test_modules(&strip_literals(&text))
}

/// The non-test `mod NAME;` declarations of `code` (a `#[cfg(test)]` on the line above leaves a
/// declaration out).
fn declared_modules(code: &str) -> Vec<String> {
    let mut names = Vec::new();
    let mut previous = "";
    for line in code.lines() {
        let l = line.trim();
        if l.is_empty() {
            continue;
        }
        let decl = l
            .strip_prefix("pub(crate) ")
            .or_else(|| l.strip_prefix("pub(super) "))
            .or_else(|| l.strip_prefix("pub "))
            .unwrap_or(l);
        if let Some(name) = decl.strip_prefix("mod ").and_then(|s| s.strip_suffix(';'))
            && previous != "#[cfg(test)]"
        {
            names.push(name.trim().to_string());
        }
        previous = l;
    }
    names
}

/// The crate's modules from its root's `mod` tree on disk.
fn module_tree(src: &Path) -> BTreeMap<ModPath, PathBuf> {
    fn walk(path: ModPath, file: PathBuf, mods: &mut BTreeMap<ModPath, PathBuf>) {
        let text = code(&file);
        let dir = file.parent().unwrap().to_path_buf();
        let base = file.file_name().unwrap().to_string_lossy().to_string();
        let here = if ["lib.rs", "main.rs", "mod.rs"].contains(&base.as_str()) {
            dir
        } else {
            dir.join(base.trim_end_matches(".rs"))
        };
        mods.insert(path.clone(), file);
        for name in declared_modules(&text) {
            for cand in [
                here.join(format!("{name}.rs")),
                here.join(&name).join("mod.rs"),
            ] {
                if cand.is_file() {
                    let mut p = path.clone();
                    p.push(name.clone());
                    walk(p, cand, mods);
                    break;
                }
            }
        }
    }
    let mut mods = BTreeMap::new();
    for root in ["lib.rs", "main.rs"] {
        let p = src.join(root);
        if p.is_file() {
            walk(Vec::new(), p, &mut mods);
            break;
        }
    }
    mods
}

/// `prefix::{a, b::{c, d}}` expanded into its paths.
fn expand_use(body: &str) -> Vec<Vec<String>> {
    fn split_top(s: &str) -> Vec<&str> {
        let (mut depth, mut start, mut parts) = (0i32, 0, Vec::new());
        for (k, ch) in s.char_indices() {
            match ch {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    parts.push(&s[start..k]);
                    start = k + 1;
                }
                _ => {}
            }
        }
        parts.push(&s[start..]);
        parts
    }
    fn go(prefix: &[String], body: &str, out: &mut Vec<Vec<String>>) {
        for part in split_top(body) {
            let p = part.trim();
            if p.is_empty() {
                continue;
            }
            if let Some(open) = p.find('{') {
                let head: Vec<String> = p[..open]
                    .split("::")
                    .map(str::trim)
                    .filter(|s| !s.is_empty())
                    .map(String::from)
                    .collect();
                let inner = &p[open + 1..p.rfind('}').unwrap_or(p.len())];
                let mut pre = prefix.to_vec();
                pre.extend(head);
                go(&pre, inner, out);
            } else {
                let p = p.split(" as ").next().unwrap().trim();
                let mut path = prefix.to_vec();
                path.extend(
                    p.split("::")
                        .map(str::trim)
                        .filter(|s| !s.is_empty())
                        .map(String::from),
                );
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    go(&[], body, &mut out);
    out
}

/// Every path the code of a file names: private `use` statements and inline
/// `crate::`/`super::`/`self::` paths (re-exports left out).
fn named_paths(code: &str) -> Vec<Vec<String>> {
    let mut paths = Vec::new();
    let mut without_reexports = String::new();
    let mut rest = code;
    // statements that start a line with `use` or `pub… use`
    while !rest.is_empty() {
        let line_end = rest.find('\n').map_or(rest.len(), |k| k + 1);
        let line = &rest[..line_end];
        let t = line.trim_start();
        let is_pub = t.starts_with("pub ") || t.starts_with("pub(");
        let after_vis = if t.starts_with("pub(") {
            t.find(')').map(|k| t[k + 1..].trim_start()).unwrap_or(t)
        } else {
            t.strip_prefix("pub ").unwrap_or(t)
        };
        if let Some(body_start) = after_vis.strip_prefix("use ") {
            let stmt_start = line.len() - body_start.len();
            let Some(semi) = rest[stmt_start..].find(';') else {
                break;
            };
            let body = &rest[stmt_start..stmt_start + semi];
            if !is_pub {
                paths.extend(expand_use(body));
            }
            rest = &rest[stmt_start + semi + 1..];
            continue;
        }
        without_reexports.push_str(line);
        rest = &rest[line_end..];
    }
    // inline paths
    let s = without_reexports;
    for head in ["crate::", "super::", "self::"] {
        let mut from = 0;
        while let Some(k) = s[from..].find(head) {
            let at = from + k;
            from = at + head.len();
            let prev = s[..at].chars().next_back();
            if prev.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let mut end = at;
            let bytes = s.as_bytes();
            loop {
                let seg_start = end;
                while end < s.len() && (bytes[end].is_ascii_alphanumeric() || bytes[end] == b'_') {
                    end += 1;
                }
                if end == seg_start {
                    break;
                }
                if s[end..].starts_with("::")
                    && s[end + 2..]
                        .chars()
                        .next()
                        .is_some_and(|c| c.is_alphabetic() || c == '_')
                {
                    end += 2;
                } else {
                    break;
                }
            }
            paths.push(s[at..end].split("::").map(String::from).collect());
        }
    }
    paths
}

/// The module a path names, as far as it names a module of this crate.
fn resolve(path: &[String], here: &ModPath, mods: &BTreeMap<ModPath, PathBuf>) -> Option<ModPath> {
    let (mut module, rest): (ModPath, &[String]) = match path.first().map(String::as_str) {
        Some("crate") => (Vec::new(), &path[1..]),
        Some("self") => (here.clone(), &path[1..]),
        Some("super") => {
            let mut m = here.clone();
            let mut r = path;
            while r.first().map(String::as_str) == Some("super") {
                m.pop();
                r = &r[1..];
            }
            (m, r)
        }
        _ => return None,
    };
    let mut best = mods.contains_key(&module).then(|| module.clone());
    for seg in rest {
        module.push(seg.clone());
        if mods.contains_key(&module) {
            best = Some(module.clone());
        } else {
            break;
        }
    }
    best
}

fn crate_graph(crate_dir: &Path) -> CrateGraph {
    let modules = module_tree(&crate_dir.join("src"));
    let mut edges: BTreeMap<PathBuf, BTreeMap<PathBuf, String>> = BTreeMap::new();
    for (here, file) in &modules {
        let entry = edges.entry(file.clone()).or_default();
        for p in named_paths(&code(file)) {
            if let Some(target) = resolve(&p, here, &modules) {
                let to = &modules[&target];
                if to != file {
                    entry.entry(to.clone()).or_insert_with(|| p.join("::"));
                }
            }
        }
    }
    CrateGraph { modules, edges }
}

/// The strongly connected sets of two or more files (Tarjan's algorithm, iterative).
fn circles(edges: &BTreeMap<PathBuf, BTreeMap<PathBuf, String>>) -> Vec<Vec<PathBuf>> {
    let nodes: Vec<&PathBuf> = edges.keys().collect();
    let index_of: BTreeMap<&PathBuf, usize> =
        nodes.iter().enumerate().map(|(i, n)| (*n, i)).collect();
    let succ: Vec<Vec<usize>> = nodes
        .iter()
        .map(|n| {
            edges[*n]
                .keys()
                .filter_map(|m| index_of.get(m).copied())
                .collect()
        })
        .collect();
    let n = nodes.len();
    let (mut index, mut low, mut on) = (vec![usize::MAX; n], vec![0; n], vec![false; n]);
    let (mut stack, mut out, mut counter) = (Vec::new(), Vec::new(), 0);
    for start in 0..n {
        if index[start] != usize::MAX {
            continue;
        }
        let mut call: Vec<(usize, usize)> = vec![(start, 0)];
        index[start] = counter;
        low[start] = counter;
        counter += 1;
        stack.push(start);
        on[start] = true;
        while let Some(&mut (v, ref mut next)) = call.last_mut() {
            if *next < succ[v].len() {
                let w = succ[v][*next];
                *next += 1;
                if index[w] == usize::MAX {
                    index[w] = counter;
                    low[w] = counter;
                    counter += 1;
                    stack.push(w);
                    on[w] = true;
                    call.push((w, 0));
                } else if on[w] {
                    low[v] = low[v].min(index[w]);
                }
            } else {
                call.pop();
                if let Some(&(parent, _)) = call.last() {
                    low[parent] = low[parent].min(low[v]);
                }
                if low[v] == index[v] {
                    let mut comp = Vec::new();
                    loop {
                        let w = stack.pop().unwrap();
                        on[w] = false;
                        comp.push(nodes[w].clone());
                        if w == v {
                            break;
                        }
                    }
                    if comp.len() > 1 {
                        comp.sort();
                        out.push(comp);
                    }
                }
            }
        }
    }
    out
}

/// One circle in words: its files, and the path that makes each file import the next.
fn describe_circle(root: &Path, graph: &CrateGraph, comp: &[PathBuf]) -> String {
    let rel = |p: &Path| p.strip_prefix(root).unwrap_or(p).display().to_string();
    let mut lines = vec![format!(
        "import circle: {}",
        comp.iter()
            .map(|p| rel(p))
            .collect::<Vec<_>>()
            .join(" <-> ")
    )];
    for from in comp {
        for (to, via) in &graph.edges[from] {
            if comp.contains(to) {
                lines.push(format!("    {} uses {} ({via})", rel(from), rel(to)));
            }
        }
    }
    lines.join("\n")
}

/// The crates whose files are checked for circles: every crate and the end-to-end tests' package.
fn crate_dirs() -> Vec<PathBuf> {
    let root = workspace();
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("src").is_dir())
        .collect();
    dirs.push(root.join("tests"));
    dirs.sort();
    dirs
}

#[test]
fn no_import_circle_between_the_source_files_of_any_crate() {
    let root = workspace();
    let mut found = Vec::new();
    let mut files = 0;
    for dir in crate_dirs() {
        let graph = crate_graph(&dir);
        files += graph.modules.len();
        for comp in circles(&graph.edges) {
            found.push(describe_circle(&root, &graph, &comp));
        }
    }
    assert!(
        files > 100,
        "only {files} source files found: is the tree where the test looks?"
    );
    assert!(
        found.is_empty(),
        "{} import circle(s) (make one side depend on the other, or move the shared piece below both):\n{}",
        found.len(),
        found.join("\n")
    );
}

/// The library's folder rules of `tests/architecture.toml`.
fn folder_rules() -> (PathBuf, BTreeMap<String, BTreeSet<String>>) {
    let path = workspace().join("tests/architecture.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let value: toml::Value = toml::from_str(&text).unwrap();
    let library = &value["library"];
    let dir = workspace().join(library["crate"].as_str().unwrap());
    let rules = library["may_use"]
        .as_table()
        .unwrap()
        .iter()
        .map(|(k, v)| {
            let allowed = v
                .as_array()
                .unwrap()
                .iter()
                .map(|s| s.as_str().unwrap().to_string())
                .collect();
            (k.clone(), allowed)
        })
        .collect();
    (dir, rules)
}

/// The folder a module of the library lies in; the crate root counts as `shared`, whose names it
/// re-exports.
fn folder(module: &ModPath) -> String {
    module
        .first()
        .cloned()
        .unwrap_or_else(|| "shared".to_string())
}

/// Every import from one folder of the library into a folder its rules do not list.
fn folder_violations(
    graph: &CrateGraph,
    rules: &BTreeMap<String, BTreeSet<String>>,
) -> Vec<String> {
    let module_of: BTreeMap<&PathBuf, &ModPath> =
        graph.modules.iter().map(|(m, f)| (f, m)).collect();
    let mut out = Vec::new();
    for (file, targets) in &graph.edges {
        let from = folder(module_of[file]);
        let Some(allowed) = rules.get(&from) else {
            out.push(format!(
                "{} lies in folder `{from}`, which tests/architecture.toml does not list",
                file.display()
            ));
            continue;
        };
        for (to_file, via) in targets {
            let to = folder(module_of[to_file]);
            if to != from && !allowed.contains(&to) {
                out.push(format!(
                    "{} (folder `{from}`) uses {} (folder `{to}`) through `{via}`; `{from}` may use: {}",
                    file.display(),
                    to_file.display(),
                    if allowed.is_empty() {
                        "no other folder".to_string()
                    } else {
                        allowed.iter().cloned().collect::<Vec<_>>().join(", ")
                    }
                ));
            }
        }
    }
    out
}

/// The module names the library's root re-exports for users' code (`pub use testbed::run;`,
/// `pub use safety::map as safety_map;`, …): lower-case names only (types such as `Error` are
/// the shared items the root stands for).
fn root_aliases(lib_rs: &Path) -> BTreeSet<String> {
    let code = code(lib_rs);
    let mut out = BTreeSet::new();
    for stmt in code.split(';') {
        let s = stmt.trim();
        let Some(body) = s.strip_prefix("pub use ") else {
            continue;
        };
        for path in expand_use(body) {
            let name = match body.rsplit_once(" as ") {
                Some((_, alias)) if !body.contains('{') => alias.trim().to_string(),
                _ => path.last().cloned().unwrap_or_default(),
            };
            if name.chars().next().is_some_and(|c| c.is_lowercase()) {
                out.insert(name);
            }
        }
    }
    out
}

/// Library files that name a module through the root's alias (`crate::run::…` for
/// `crate::testbed::run::…`): the folder rules could not see where such a path leads.
fn alias_uses(graph: &CrateGraph, aliases: &BTreeSet<String>) -> Vec<String> {
    let mut out = Vec::new();
    for (module, file) in &graph.modules {
        if module.is_empty() {
            continue;
        }
        for p in named_paths(&code(file)) {
            if p.first().map(String::as_str) == Some("crate")
                && p.get(1).is_some_and(|n| aliases.contains(n))
            {
                out.push(format!(
                    "{} names `{}` through the root's alias `crate::{}`: use the folder's path",
                    file.display(),
                    p.join("::"),
                    p[1]
                ));
            }
        }
    }
    out
}

#[test]
fn the_library_folders_import_one_way() {
    let (dir, rules) = folder_rules();
    let graph = crate_graph(&dir);
    // every folder on disk has its rule, and the rules run one way (no circle among the folders)
    for module in graph.modules.keys() {
        if module.len() == 1 && graph.modules[module].ends_with("mod.rs") {
            assert!(
                rules.contains_key(&module[0]),
                "folder `{}` has no rule in tests/architecture.toml",
                module[0]
            );
        }
    }
    let mut folder_edges: BTreeMap<PathBuf, BTreeMap<PathBuf, String>> = BTreeMap::new();
    for (k, v) in &rules {
        folder_edges.insert(
            PathBuf::from(k),
            v.iter()
                .map(|t| (PathBuf::from(t), String::new()))
                .collect(),
        );
    }
    let loops = circles(&folder_edges);
    assert!(
        loops.is_empty(),
        "the folder rules themselves run in a circle: {loops:?}"
    );
    let bad = folder_violations(&graph, &rules);
    assert!(
        bad.is_empty(),
        "imports against the folder rules:\n{}",
        bad.join("\n")
    );
    let aliases = root_aliases(&dir.join("src/lib.rs"));
    assert!(
        aliases.contains("run") && aliases.contains("safety_map"),
        "{aliases:?}"
    );
    let through_aliases = alias_uses(&graph, &aliases);
    assert!(through_aliases.is_empty(), "{}", through_aliases.join("\n"));
}

/// A throw-away crate on disk for the checks' own tests.
fn scratch_crate(name: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "flexrig-architecture-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    for (path, text) in files {
        let p = dir.join("src").join(path);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, text).unwrap();
    }
    dir
}

#[test]
fn the_check_finds_a_circle_and_names_its_files_and_paths() {
    let dir = scratch_crate(
        "circle",
        &[
            (
                "lib.rs",
                "pub mod a;\npub mod b;\npub mod c;\n#[cfg(test)]\nmod t;\n",
            ),
            ("a.rs", "use crate::b::B;\npub struct A;\n"),
            // an inline path in code, a path in a comment and one in a string
            (
                "b.rs",
                "pub struct B;\n// crate::c::C\nfn f() { let _ = \"crate::c\"; let _ = crate::a::A; }\n",
            ),
            // a re-export and a test module do not count
            (
                "c.rs",
                "pub use crate::a::A;\n#[cfg(test)]\nmod tests {\n use crate::b::B;\n}\npub struct C;\n",
            ),
            ("t.rs", "use crate::c::C;\n"),
        ],
    );
    let graph = crate_graph(&dir);
    assert_eq!(
        graph.modules.len(),
        4,
        "the test module t is not part of the tree"
    );
    let found = circles(&graph.edges);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0], vec![dir.join("src/a.rs"), dir.join("src/b.rs")]);
    let text = describe_circle(&dir, &graph, &found[0]);
    assert!(
        text.contains("src/a.rs uses src/b.rs (crate::b::B)"),
        "{text}"
    );
    assert!(
        text.contains("src/b.rs uses src/a.rs (crate::a::A)"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_check_finds_an_import_against_the_folder_rules() {
    let dir = scratch_crate(
        "folders",
        &[
            (
                "lib.rs",
                "pub mod low;\npub mod high;\npub use low::x::Error;\n",
            ),
            ("low/mod.rs", "pub mod x;\n"),
            (
                "low/x.rs",
                "pub struct Error;\nuse super::super::high::y::Y;\n",
            ),
            ("high/mod.rs", "pub mod y;\n"),
            (
                "high/y.rs",
                "pub struct Y;\nuse crate::Error;\nuse crate::low::{x::{Error as E}};\n",
            ),
        ],
    );
    let graph = crate_graph(&dir);
    let rules: BTreeMap<String, BTreeSet<String>> = [
        ("shared".to_string(), BTreeSet::new()),
        ("low".to_string(), BTreeSet::new()),
        (
            "high".to_string(),
            ["low".to_string(), "shared".to_string()].into(),
        ),
    ]
    .into();
    let bad = folder_violations(&graph, &rules);
    assert_eq!(bad.len(), 1, "{bad:?}");
    assert!(
        bad[0].contains("low/x.rs (folder `low`) uses"),
        "{}",
        bad[0]
    );
    assert!(
        bad[0].contains("through `super::super::high::y::Y`"),
        "{}",
        bad[0]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_check_finds_a_path_through_a_root_alias() {
    let dir = scratch_crate(
        "aliases",
        &[
            (
                "lib.rs",
                "pub mod low;\npub mod high;\npub use low::x as old_x;\npub use low::{x, Error};\n",
            ),
            ("low/mod.rs", "pub mod x;\n"),
            ("low/x.rs", "pub struct Error;\n"),
            ("high/mod.rs", "pub mod y;\n"),
            (
                "high/y.rs",
                "use crate::old_x::Error;\nuse crate::Error as E;\nuse crate::low::x::Error as F;\n",
            ),
        ],
    );
    let graph = crate_graph(&dir);
    let aliases = root_aliases(&dir.join("src/lib.rs"));
    assert_eq!(aliases, ["old_x".to_string(), "x".to_string()].into());
    let found = alias_uses(&graph, &aliases);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].contains("crate::old_x::Error"), "{}", found[0]);
    let _ = std::fs::remove_dir_all(&dir);
}
