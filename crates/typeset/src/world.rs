//! The sandbox the typesetter runs in: a typst `World` that serves the template, its assets,
//! the data file and the bundled fonts, and nothing else (no file system, no packages, no
//! network, no clock).

use std::collections::HashMap;
use std::sync::{LazyLock, Mutex};

use typst::diag::{FileError, FileResult};
use typst::foundations::{Bytes, Datetime, Duration};
use typst::syntax::{FileId, RootedPath, Source, VirtualPath, VirtualRoot};
use typst::text::{Font, FontBook};
use typst::utils::LazyHash;
use typst::{Library, LibraryExt as _, World};

use crate::error::TypesetError;
use crate::template::{DATA_PATH, Template};

/// The fonts typst bundles (typst-assets: Libertinus Serif, New Computer Modern and its math,
/// DejaVu Sans Mono), parsed once per process.
pub(crate) static FONTS: LazyLock<(LazyHash<FontBook>, Vec<Font>)> = LazyLock::new(|| {
    let fonts: Vec<Font> = typst_assets::fonts()
        .flat_map(|data| Font::iter(Bytes::new(data)))
        .collect();
    (LazyHash::new(FontBook::from_fonts(&fonts)), fonts)
});

/// The standard library without inputs or features, built once.
static LIBRARY: LazyLock<LazyHash<Library>> = LazyLock::new(|| LazyHash::new(Library::default()));

/// A file the world serves: its bytes, and its text when it is the template.
struct Served {
    bytes: Bytes,
    source: Option<Source>,
}

/// The world of one compilation.
pub(crate) struct Sandbox {
    main: FileId,
    files: HashMap<FileId, Served>,
    /// Every path the document asked for that the world does not serve, in order.
    denied: Mutex<Vec<String>>,
}

/// The id of a path in the project's root.
fn id_of(path: &str) -> Result<FileId, String> {
    let vpath = VirtualPath::new(path).map_err(|e| format!("{e:?}"))?;
    Ok(RootedPath::new(VirtualRoot::Project, vpath).intern())
}

impl Sandbox {
    /// The world of `template` with `data` served at [`DATA_PATH`].
    pub(crate) fn new(template: &Template<'_>, data: &[u8]) -> Result<Self, TypesetError> {
        let bad_path = |path: &str, reason: String| TypesetError::AssetPath {
            path: path.to_owned(),
            reason,
        };
        let main_path = format!("/{}", template.name.trim_start_matches('/'));
        let main = id_of(&main_path).map_err(|r| bad_path(&main_path, r))?;
        let mut files = HashMap::new();
        files.insert(
            main,
            Served {
                bytes: Bytes::from_string(template.source.to_owned()),
                source: Some(Source::new(main, template.source.to_owned())),
            },
        );
        let data_id = id_of(DATA_PATH).map_err(|r| bad_path(DATA_PATH, r))?;
        files.insert(
            data_id,
            Served {
                bytes: Bytes::new(data.to_vec()),
                source: None,
            },
        );
        for asset in template.assets {
            let id = id_of(asset.path).map_err(|r| bad_path(asset.path, r))?;
            if files.contains_key(&id) {
                return Err(bad_path(
                    asset.path,
                    "served twice (the template, the data file or another asset)".to_owned(),
                ));
            }
            files.insert(
                id,
                Served {
                    bytes: Bytes::new(asset.bytes.to_vec()),
                    source: None,
                },
            );
        }
        Ok(Self {
            main,
            files,
            denied: Mutex::new(Vec::new()),
        })
    }

    /// The paths the document asked for and was refused.
    pub(crate) fn denied(&self) -> Vec<String> {
        self.denied
            .lock()
            .map_or_else(|e| e.into_inner().clone(), |d| d.clone())
    }

    fn refuse(&self, id: FileId) -> FileError {
        let path = format!("{:?}", id.get());
        match self.denied.lock() {
            Ok(mut d) => d.push(path),
            Err(e) => e.into_inner().push(path),
        }
        FileError::AccessDenied
    }
}

impl World for Sandbox {
    fn library(&self) -> &LazyHash<Library> {
        &LIBRARY
    }

    fn book(&self) -> &LazyHash<FontBook> {
        &FONTS.0
    }

    fn main(&self) -> FileId {
        self.main
    }

    fn source(&self, id: FileId) -> FileResult<Source> {
        match self.files.get(&id) {
            Some(Served {
                source: Some(s), ..
            }) => Ok(s.clone()),
            Some(_) => Err(FileError::NotSource),
            None => Err(self.refuse(id)),
        }
    }

    fn file(&self, id: FileId) -> FileResult<Bytes> {
        self.files
            .get(&id)
            .map(|f| f.bytes.clone())
            .ok_or_else(|| self.refuse(id))
    }

    fn font(&self, index: usize) -> Option<Font> {
        FONTS.1.get(index).cloned()
    }

    /// No clock: a document states the dates its data gives (`datetime.today()` is an
    /// error), so the same data always typesets to the same bytes.
    fn today(&self, _offset: Option<Duration>) -> Option<Datetime> {
        None
    }
}
