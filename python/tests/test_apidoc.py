"""The book's Python API page is what the package's docstrings and signatures say."""

from conftest import REPO


def test_the_books_api_page_is_what_the_package_writes():
    from covga import _apidoc

    page = REPO / "docs" / "src" / "guide" / "python-api.md"
    written = _apidoc.markdown()
    assert page.read_text() == written, (
        "docs/src/guide/python-api.md is not what the package writes: re-make it with "
        "`python -m covga._apidoc > docs/src/guide/python-api.md` in the package's environment"
    )
    for name in ("covga.load_map", "covga.score", "covga.thesis.evaluate", "covga.stats.wilcoxon"):
        assert f"### `{name}`" in written, name
