//! Hostile text through the study's free-text fields (issue 27, part 5): the study name, where
//! g comes from, every text of the certificate section and a recording's file name carry
//! markup, script, style, links, terminal escapes and bidirectional overrides. No output holds
//! an active element or a reference that loads anything: report.md has no HTML tag and no
//! Markdown image or link made of the payload, the SVG figures are well-formed and hold no
//! script, foreign object or external reference, the terminal gets no ESC, BEL or override,
//! results.json reads back. Hidden characters are refused where text identifies (the study's
//! name, the certificate's fields), naming the field.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Payloads a printable-text field accepts (every one is shown as text).
const PRINTABLE: &[&str] = &[
    "</style><script>alert(1)</script>",
    "\"><img src=x onerror=alert(1)>",
    "javascript:alert(1)",
    "x{} body{background:url(http://evil.invalid/x)}",
    "@import url(http://evil.invalid/a.css);",
    "<iframe src=file:///etc/passwd></iframe>",
    "![x](http://evil.invalid/p.png) [click](javascript:alert(1)) `code` *em* | cell |",
    "<svg onload=alert(1)><foreignObject><a xlink:href=\"http://evil.invalid\">x</a>",
    "#read(\"/etc/passwd\") #image(\"/etc/passwd\") $x$ \\ ] [ ] #",
    "&lt;script&gt; &amp; &#60;b&#62;",
];

/// Payloads with hidden characters (terminal escapes, a bidirectional override, NUL).
const HIDDEN: &[&str] = &[
    "\u{1b}]0;pwned\u{7}\u{1b}[2J",
    "SN \u{202e}evil\u{202c} 1234",
    "nul\u{0}byte",
];

/// RON string literal of `text`.
fn ron(text: &str) -> String {
    let mut out = String::from("\"");
    for c in text.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() || ('\u{202a}'..='\u{2069}').contains(&c) => {
                out.push_str(&format!("\\u{{{:04x}}}", u32::from(c)));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// The campaign study in `dir` (its data copied beside it, one PIGA recording renamed to
/// `file_name`), with `name`, `g_source` and every text of the certificate section replaced.
fn poisoned_study(dir: &Path, name: &str, g_source: &str, certificate_text: &str) -> PathBuf {
    let data = dir.join("campaign");
    std::fs::create_dir_all(&data).unwrap();
    for e in std::fs::read_dir(root().join("fixtures/campaign")).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), data.join(e.file_name())).unwrap();
    }
    let file_name = "`x`<script>alert(1)<\\script>|*[a](b).csv";
    std::fs::rename(
        data.join("piga_100.0000deg_s.csv"),
        data.join(file_name.replace('\\', "_")),
    )
    .unwrap();
    let mut text = std::fs::read_to_string(root().join("fixtures/studies/campaign.ron")).unwrap();
    text = text.replace("\"../campaign/", "\"campaign/");
    text = text.replace(
        "\"campaign/piga_100.0000deg_s.csv\"",
        &ron(&format!("campaign/{}", file_name.replace('\\', "_"))),
    );
    text = text.replacen("name: \"campaign\"", &format!("name: {}", ron(name)), 1);
    text = text.replace(
        "g_source: \"nominal 9.8 m/s², the value the simulation used\"",
        &format!("g_source: {}", ron(g_source)),
    );
    // every string of the certificate section
    let start = text.find("    certificate: (").unwrap();
    let (head, cert) = text.split_at(start);
    let mut out = String::new();
    let mut rest = cert;
    while let Some(i) = rest.find(": \"") {
        out.push_str(&rest[..i + 2]);
        let after = &rest[i + 3..];
        let end = after.find('"').unwrap();
        let value = &after[..end];
        if is_iso_date(value) || is_country(value) {
            // a date or a country code is not free text: refused unless ISO (a test below)
            out.push_str(&ron(value));
        } else {
            out.push_str(&ron(&format!("{value} {certificate_text}")));
        }
        rest = &after[end + 1..];
    }
    out.push_str(rest);
    let path = dir.join("study.ron");
    std::fs::write(&path, format!("{head}{out}")).unwrap();
    path
}

/// `YYYY-MM-DD`, or two of them joined by ` to `.
fn is_iso_date(text: &str) -> bool {
    if let Some((a, b)) = text.split_once(" to ") {
        return is_iso_date(a) && is_iso_date(b);
    }
    let b = text.as_bytes();
    b.len() == 10
        && b.iter().enumerate().all(|(i, c)| {
            if i == 4 || i == 7 {
                *c == b'-'
            } else {
                c.is_ascii_digit()
            }
        })
}

/// Two capital letters (ISO 3166-1 alpha-2).
fn is_country(text: &str) -> bool {
    text.len() == 2 && text.bytes().all(|c| c.is_ascii_uppercase())
}

fn study(config: &Path, out: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_centrifuge-cal"))
        .args(["study", "--no-compare", "--config"])
        .arg(config)
        .arg("--out")
        .arg(out)
        .output()
        .expect("runs")
}

/// Whether `text` holds an HTML or SVG tag: `<` followed by a letter, `/`, `!` or `?`.
fn has_tag(text: &str) -> bool {
    text.as_bytes()
        .windows(2)
        .any(|w| w[0] == b'<' && (w[1].is_ascii_alphabetic() || matches!(w[1], b'/' | b'!' | b'?')))
}

fn hidden(text: &str) -> Option<char> {
    text.chars().find(|&c| {
        (c.is_control() && c != '\n' && c != '\t') || ('\u{202a}'..='\u{2069}').contains(&c)
    })
}

/// The SVG is well-formed XML whose tags hold no script, style, foreign object, image, event
/// handler or reference that loads anything (the payload may appear as text, escaped).
fn assert_inert_svg(name: &str, svg: &str) {
    assert_eq!(hidden(svg), None, "{name} holds a hidden character");
    let mut stack: Vec<String> = Vec::new();
    let mut rest = svg;
    while let Some(i) = rest.find('<') {
        rest = &rest[i + 1..];
        let end = rest
            .find('>')
            .unwrap_or_else(|| panic!("{name}: an unclosed tag"));
        let tag = &rest[..end];
        rest = &rest[end + 1..];
        if tag.starts_with('?') || tag.starts_with("!--") {
            continue;
        }
        let lower = tag.to_ascii_lowercase();
        let element = lower
            .trim_start_matches('/')
            .split_whitespace()
            .next()
            .unwrap_or("")
            .trim_end_matches('/')
            .to_owned();
        for bad in [
            "script",
            "style",
            "foreignobject",
            "iframe",
            "img",
            "image",
            "use",
            "a",
        ] {
            assert_ne!(element, bad, "{name} holds the element <{element}>");
        }
        for bad in ["href", "@import", "javascript:"] {
            assert!(!lower.contains(bad), "{name}: a tag holds {bad}: <{tag}>");
        }
        // only references within the document (`url(#clip3)`)
        for (at, _) in lower.match_indices("url(") {
            let target = lower[at + 4..].trim_start_matches(['"', '\'']);
            assert!(
                target.starts_with('#'),
                "{name}: a tag loads {target}: <{tag}>"
            );
        }
        let handler = lower
            .split_whitespace()
            .any(|a| a.starts_with("on") && a.contains('='));
        assert!(!handler, "{name}: an event handler in <{tag}>");
        if let Some(closing) = tag.strip_prefix('/') {
            assert_eq!(
                stack.pop().as_deref(),
                Some(closing.trim()),
                "{name}: tags out of order"
            );
        } else if !tag.ends_with('/') {
            stack.push(tag.split_whitespace().next().unwrap().to_owned());
        }
    }
    assert!(stack.is_empty(), "{name}: unclosed {stack:?}");
}

#[test]
fn hostile_text_in_every_free_text_field_stays_text() {
    for (i, payload) in PRINTABLE.iter().enumerate() {
        let g_source = format!("{payload} {}", HIDDEN[i % HIDDEN.len()]);
        let dir = test_support::Scratch::new(&format!("cli-hostile-text-{i}"));
        let config = poisoned_study(dir.path(), payload, &g_source, payload);
        let out = dir.path().join("out");
        let run = study(&config, &out);
        let stdout = String::from_utf8(run.stdout).unwrap();
        let stderr = String::from_utf8(run.stderr).unwrap();
        assert!(run.status.success(), "payload {i}: {stderr}");
        // the terminal: the payload is shown, no hidden character reaches it
        assert_eq!(hidden(&stdout), None, "payload {i}: stdout");
        assert_eq!(hidden(&stderr), None, "payload {i}: stderr");
        assert!(
            stdout.contains(payload),
            "payload {i}: the summary names the study"
        );
        // report.md: no tag, no image or link made of the payload
        let report = std::fs::read_to_string(out.join("report.md")).unwrap();
        assert!(!has_tag(&report), "payload {i}: report.md holds a tag");
        assert!(
            !report.contains("![x]("),
            "payload {i}: report.md holds an image"
        );
        assert!(
            !report.contains("[click]("),
            "payload {i}: report.md holds a link"
        );
        assert_eq!(hidden(&report), None, "payload {i}: report.md");
        assert!(
            report.contains("\\`x\\`"),
            "payload {i}: the file name is escaped"
        );
        // the figures
        for e in std::fs::read_dir(&out).unwrap() {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            if name.ends_with(".svg") {
                assert_inert_svg(&name, &std::fs::read_to_string(e.path()).unwrap());
            }
        }
        // results.json reads back with the payload as it was given
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap())
                .unwrap();
        assert_eq!(json["study"], *payload);
        assert_eq!(json["calibration"]["g_source"], g_source.as_str());
    }
}

#[test]
fn hidden_characters_in_identifying_text_are_refused_naming_the_field() {
    for (i, payload) in HIDDEN.iter().enumerate() {
        let dir = test_support::Scratch::new(&format!("cli-hostile-hidden-{i}"));
        let config = poisoned_study(dir.path(), payload, "g", "x");
        let run = study(&config, &dir.path().join("out"));
        let stderr = String::from_utf8(run.stderr).unwrap();
        assert!(!run.status.success());
        assert!(
            stderr.contains("field `name` holds the character U+"),
            "{stderr}"
        );
        assert_eq!(hidden(&stderr), None, "{stderr}");
        assert!(!dir.path().join("out").exists());

        let config = poisoned_study(dir.path(), "campaign", "g", payload);
        let run = study(&config, &dir.path().join("out"));
        let stderr = String::from_utf8(run.stderr).unwrap();
        assert!(!run.status.success());
        assert!(
            stderr.contains("field `certificate.id` holds the character U+"),
            "{stderr}"
        );
        assert!(
            stderr.contains("field `certificate.item.serial` holds"),
            "{stderr}"
        );
        assert_eq!(hidden(&stderr), None, "{stderr}");
    }
}

#[test]
fn a_date_that_is_not_iso_is_refused_naming_its_field() {
    let dir = test_support::Scratch::new("cli-hostile-date");
    let config = poisoned_study(dir.path(), "campaign", "nominal", "");
    let text = std::fs::read_to_string(&config).unwrap();
    let start = text
        .find("received: \"")
        .expect("the fixture states the date received")
        + 11;
    let poisoned = format!(
        "{}2026-11-16 </style><script>{}",
        &text[..start],
        &text[start + 10..]
    );
    std::fs::write(&config, poisoned).unwrap();
    let out = dir.path().join("out");
    let run = study(&config, &out);
    let stderr = String::from_utf8(run.stderr).unwrap();
    assert!(!run.status.success());
    assert!(stderr.contains("certificate.dates.received"), "{stderr}");
    assert_eq!(hidden(&stderr), None);
    assert!(!out.join("certificate.pdf").exists());
}
