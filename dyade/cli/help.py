"""``dyade help``: the documentation pages that come with dyade (its file references and
user guide, ``dyade/pages``: the pages of docs/reference and docs/guide), on the terminal,
so that a pip user has them without the repository."""

from __future__ import annotations

import click

from dyade.cli import main


def pages() -> dict[str, str]:
    """topic -> its page's title, every page that comes with dyade, sorted."""
    out = {}
    for page in sorted(_folder().iterdir(), key=lambda p: p.name):
        if page.name.endswith(".md"):
            out[page.name[:-3]] = _title(page.read_text(encoding="utf-8"))
    return out


def page(topic: str) -> str:
    """The Markdown text of ``topic``'s page (its notebook header left out); a
    ``click.UsageError`` with the topics close to it where there is none."""
    known = pages()
    name = topic.lower().removesuffix(".md")
    if name not in known:
        import difflib

        close = difflib.get_close_matches(name, list(known), n=3, cutoff=0.5)
        hint = f" Did you mean {', '.join(close)}?" if close else ""
        raise click.UsageError(f"no help topic {topic!r}.{hint} The topics: "
                               f"{', '.join(known)}.")
    text = _folder().joinpath(f"{name}.md").read_text(encoding="utf-8")
    if text.startswith("---\n"):  # MyST front matter (a notebook page's kernel)
        text = text.split("\n---\n", 1)[-1].lstrip("\n")
    return text


def _folder():
    from importlib.resources import files

    return files("dyade").joinpath("pages")


def _title(text: str) -> str:
    for line in text.splitlines():
        if line.startswith("# "):
            return line[2:].strip()
    return ""


@main.command("help")
@click.argument("topic", required=False)
def help_(topic: str | None) -> None:
    """The documentation that comes with dyade, by TOPIC: every key of a mechanism,
    gear-drive, coupling or study file, every column and figure of the output, and a
    user-guide page per analysis. Without TOPIC: the topics.

    \b
        dyade help                   # the topics
        dyade help mechanism-file    # every key of a mechanism file
        dyade help columns | less    # every column of the CSV

    On a terminal the page is shown formatted; into a pipe or a file as its Markdown.
    The same pages, with figures, make the documentation site (docs/ in the repository).
    """
    import sys

    if topic is None:
        known = pages()
        width = max(map(len, known))
        click.echo("dyade help TOPIC, the topics:")
        for name, title in known.items():
            click.echo(f"  {name:<{width}}  {title}")
        return
    text = page(topic)
    if not sys.stdout.isatty():
        click.echo(text, nl=not text.endswith("\n"))
        return
    from rich.markdown import Markdown

    from dyade.cli.output import console

    console().print(Markdown(text))
