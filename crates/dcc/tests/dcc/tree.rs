//! A small element tree of a written DCC, read back with quick-xml's reader, and the
//! helpers the tests find elements with.

use quick_xml::events::Event;
use quick_xml::{Reader, XmlVersion};

/// An element: its name, attributes, text (character data and resolved references) and
/// children.
#[derive(Debug, Clone, Default)]
pub(crate) struct Node {
    pub(crate) name: String,
    pub(crate) attributes: Vec<(String, String)>,
    pub(crate) text: String,
    pub(crate) children: Vec<Node>,
}

impl Node {
    /// Parses `xml`, panicking with the reader's error on a document that is not well-formed.
    pub(crate) fn parse(xml: &str) -> Self {
        let mut reader = Reader::from_str(xml);
        let mut stack = vec![Node::default()];
        loop {
            match reader.read_event().expect("well-formed XML") {
                Event::Start(e) => stack.push(Self::start(&e)),
                Event::Empty(e) => {
                    let node = Self::start(&e);
                    stack.last_mut().unwrap().children.push(node);
                }
                Event::End(_) => {
                    let node = stack.pop().unwrap();
                    stack.last_mut().unwrap().children.push(node);
                }
                Event::Text(t) => stack.last_mut().unwrap().text.push_str(&t.xml10_content()),
                Event::GeneralRef(r) => {
                    let text = match r.resolve_char_ref().expect("a valid reference") {
                        Some(c) => c.to_string(),
                        None => match &*r.xml10_content() {
                            "lt" => "<".to_owned(),
                            "gt" => ">".to_owned(),
                            "amp" => "&".to_owned(),
                            "apos" => "'".to_owned(),
                            "quot" => "\"".to_owned(),
                            other => panic!("undeclared entity &{other};"),
                        },
                    };
                    stack.last_mut().unwrap().text.push_str(&text);
                }
                Event::CData(_) | Event::PI(_) | Event::DocType(_) => {
                    panic!("the DCC holds no CDATA, processing instruction or DTD")
                }
                Event::Eof => break,
                Event::Decl(_) | Event::Comment(_) => {}
            }
        }
        assert_eq!(stack.len(), 1, "unclosed elements");
        let mut root = stack.pop().unwrap();
        assert_eq!(root.children.len(), 1, "one root element");
        root.children.pop().unwrap()
    }

    fn start(e: &quick_xml::events::BytesStart<'_>) -> Self {
        Node {
            name: e.name().as_ref().to_owned(),
            attributes: e
                .attributes()
                .map(|a| {
                    let a = a.expect("a well-formed attribute");
                    (
                        a.key.as_ref().to_owned(),
                        a.normalized_value(XmlVersion::Implicit1_0)
                            .expect("an escaped value")
                            .into_owned(),
                    )
                })
                .collect(),
            ..Node::default()
        }
    }

    /// The value of attribute `key`.
    pub(crate) fn attribute(&self, key: &str) -> Option<&str> {
        self.attributes
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }

    /// Every element below (and including) this one, depth first.
    pub(crate) fn descendants(&self) -> Vec<&Node> {
        let mut all = vec![self];
        for c in &self.children {
            all.extend(c.descendants());
        }
        all
    }

    /// The element with attribute `id` = `id`.
    pub(crate) fn by_id(&self, id: &str) -> &Node {
        self.descendants()
            .into_iter()
            .find(|n| n.attribute("id") == Some(id))
            .unwrap_or_else(|| panic!("no element with id {id}"))
    }

    /// The first element named `name` below this one (a path of names separated by `/`).
    pub(crate) fn find(&self, path: &str) -> &Node {
        self.try_find(path)
            .unwrap_or_else(|| panic!("no {path} in {}", self.name))
    }

    /// The same, if there is one.
    pub(crate) fn try_find(&self, path: &str) -> Option<&Node> {
        let mut node = self;
        for name in path.split('/') {
            node = node
                .descendants()
                .into_iter()
                .skip(1)
                .find(|n| n.name == name)?;
        }
        Some(node)
    }

    /// Every element named `name` below this one.
    pub(crate) fn all(&self, name: &str) -> Vec<&Node> {
        self.descendants()
            .into_iter()
            .skip(1)
            .filter(|n| n.name == name)
            .collect()
    }

    /// The text of the element at `path`, parsed as a number.
    pub(crate) fn number(&self, path: &str) -> f64 {
        let text = &self.find(path).text;
        text.parse()
            .unwrap_or_else(|e| panic!("{path} = {text:?}: {e}"))
    }
}
