"""Downloads one pinned wheel with Python's standard library alone: build.rs's way where
python3 has no pip (inside pip's build isolation, or a bare system Python).

    python3 build/fetch_wheel.py NAME==VERSION SHA256 DIR

Reads the project's page on the package index (PEP 691 JSON or PEP 503 HTML, whichever the
index serves; `PIP_INDEX_URL` if set, else https://pypi.org/simple), takes the one file the
page lists with the pinned SHA-256, and saves it into DIR under its own name, checking the
digest of the bytes received. build.rs checks the digest of the saved file again. Errors go
to stderr as one line (build.rs quotes the last line) and exit 1.
"""
import hashlib
import html
import json
import os
import re
import sys
import urllib.parse
import urllib.request

ACCEPT = "application/vnd.pypi.simple.v1+json, text/html;q=0.1"


def get(url, **headers):
    """The open response for `url`; a failure names the URL."""
    try:
        return urllib.request.urlopen(urllib.request.Request(url, headers=headers), timeout=60)
    except OSError as e:  # URLError, HTTPError, timeouts
        raise RuntimeError(f"{url}: {getattr(e, 'reason', None) or e}") from e


def file_urls(page, sha256):
    """The URLs on the project page `page` whose listed SHA-256 is `sha256`."""
    with get(page, Accept=ACCEPT) as response:
        kind = response.headers.get("Content-Type", "")
        body = response.read().decode("utf-8")
    if "json" in kind:
        files = json.loads(body)["files"]
        urls = [f["url"] for f in files if f.get("hashes", {}).get("sha256") == sha256]
    else:
        hrefs = (html.unescape(h) for h in re.findall(r'href="([^"]+)"', body))
        urls = [h for h in hrefs if urllib.parse.urldefrag(h)[1] == "sha256=" + sha256]
    return [urllib.parse.urldefrag(urllib.parse.urljoin(page, u))[0] for u in urls]


def fetch(pin, sha256, out):
    name = pin.split("==")[0]
    index = os.environ.get("PIP_INDEX_URL", "https://pypi.org/simple").rstrip("/") + "/"
    page = urllib.parse.urljoin(index, re.sub(r"[-_.]+", "-", name).lower() + "/")
    urls = file_urls(page, sha256)
    if not urls:
        raise RuntimeError(f"{page} lists no file with the pinned SHA-256 of {pin} ({sha256})")
    url = urls[0]
    filename = urllib.parse.unquote(urllib.parse.urlparse(url).path.rsplit("/", 1)[-1])
    if not filename.endswith(".whl") or filename.startswith("."):
        raise RuntimeError(f"{url} is not a wheel")
    part = os.path.join(out, filename + ".part")
    digest = hashlib.sha256()
    with get(url) as response, open(part, "wb") as file:
        while chunk := response.read(1 << 20):
            digest.update(chunk)
            file.write(chunk)
    if digest.hexdigest() != sha256:
        os.remove(part)
        raise RuntimeError(f"{url}: SHA-256 {digest.hexdigest()}, expected {sha256}")
    os.replace(part, os.path.join(out, filename))


if __name__ == "__main__":
    try:
        fetch(*sys.argv[1:4])
    except Exception as e:  # one line for build.rs, whatever failed
        print(f"fetch_wheel: {type(e).__name__}: {e}", file=sys.stderr)
        sys.exit(1)
