//! The XML writer: quick-xml's event writer under a small interface that takes element names
//! the code spells and text only as [`Text`] (checked: see `text.rs`), so that nothing from
//! the configuration or a file reaches the document but as escaped character data.

use quick_xml::Writer;
use quick_xml::escape::partial_escape;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, BytesText, Event};

use crate::error::Result;
use crate::text::Text;

/// The language of every text (`usedLangCodeISO639_1`).
pub(crate) const LANG: &str = "en";

/// A DCC document being written.
pub(crate) struct Xml {
    writer: Writer<Vec<u8>>,
}

impl Xml {
    /// A document with its XML declaration, indented by two spaces.
    pub(crate) fn new() -> Result<Self> {
        let mut writer = Writer::new_with_indent(Vec::new(), b' ', 2);
        writer.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
        Ok(Self { writer })
    }

    /// Element `name` (with attributes the code spells, or an `id` it composes) around what
    /// `inner` writes.
    pub(crate) fn el_with(
        &mut self,
        name: &'static str,
        attributes: &[(&'static str, &str)],
        inner: impl FnOnce(&mut Self) -> Result<()>,
    ) -> Result<()> {
        let mut start = BytesStart::new(name);
        for (key, value) in attributes {
            // the writer escapes the value
            start.push_attribute((*key, *value));
        }
        self.writer.write_event(Event::Start(start))?;
        inner(self)?;
        self.writer.write_event(Event::End(BytesEnd::new(name)))?;
        Ok(())
    }

    /// Element `name` around what `inner` writes.
    pub(crate) fn el(
        &mut self,
        name: &'static str,
        inner: impl FnOnce(&mut Self) -> Result<()>,
    ) -> Result<()> {
        self.el_with(name, &[], inner)
    }

    /// Element `name` holding `text`, escaped.
    pub(crate) fn leaf(&mut self, name: &'static str, text: &Text) -> Result<()> {
        self.writer
            .write_event(Event::Start(BytesStart::new(name)))?;
        self.text(text)?;
        self.writer.write_event(Event::End(BytesEnd::new(name)))?;
        Ok(())
    }

    /// Element `name` holding the writer's own words.
    pub(crate) fn own(&mut self, name: &'static str, text: &str) -> Result<()> {
        self.leaf(name, &Text::own(text))
    }

    /// A `dcc:textType` or `dcc:richContentType` element `name` holding one English
    /// `dcc:content`.
    pub(crate) fn content(&mut self, name: &'static str, text: &Text) -> Result<()> {
        self.el(name, |x| {
            x.el_with("dcc:content", &[("lang", LANG)], |x| x.text(text))
        })
    }

    /// A `dcc:textType` or `dcc:richContentType` element of the writer's own words.
    pub(crate) fn own_content(&mut self, name: &'static str, text: &str) -> Result<()> {
        self.content(name, &Text::own(text))
    }

    /// Character data, escaped by quick-xml's `partial_escape` (`<`, `>`, `&` and CR, which
    /// XML would read as LF; quotes need no escape in character data).
    fn text(&mut self, text: &Text) -> Result<()> {
        self.writer
            .write_event(Event::Text(BytesText::from_escaped(partial_escape(
                text.as_str(),
            ))))?;
        Ok(())
    }

    /// The document's text.
    pub(crate) fn finish(self) -> String {
        let mut bytes = self.writer.into_inner();
        bytes.push(b'\n');
        // every byte written came from `&str`s and ASCII markup
        String::from_utf8(bytes)
            .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
    }
}
