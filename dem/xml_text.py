"""Text in the XML files dem writes (VTK, XDMF): escaped here rather than by xml.sax.saxutils, whose import
pulls in urllib.request (12 ms of every start-up)."""

_TEXT = (("&", "&amp;"), ("<", "&lt;"), (">", "&gt;"))
_ATTRIBUTE = _TEXT + (('"', "&quot;"), ("\n", "&#10;"), ("\r", "&#13;"), ("\t", "&#9;"))


def escape(text):
    """`text` as XML character data."""
    for raw, entity in _TEXT:
        text = text.replace(raw, entity)
    return text


def quoteattr(value):
    """`value` as a double-quoted XML attribute value."""
    for raw, entity in _ATTRIBUTE:
        value = value.replace(raw, entity)
    return f'"{value}"'
