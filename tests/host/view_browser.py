"""The browser test of uuvsim view: headless Chromium opens mission.html.

    view_browser.py PAGE.html [T_A T_B]
    view_browser.py --live URL      (the live view of uuvsim --view)

Drives one Chromium (software GL, SwiftShader) through the DevTools
protocol on a pipe (--remote-debugging-pipe) and checks that
  - the page loads and says so in its title ("mission: ok"), with no
    exception and no error on the console;
  - the vehicle is drawn: at time T_A the 3-D view with the vehicle differs
    from the same view without it (#vehicle=0);
  - moving the time slider to T_B moves the vehicle: where the vehicle was
    at T_A the view has changed, and the vehicle's pixels have moved.
With --live it opens the page of a running `uuvsim --view` and checks
that it loads, that frames arrive while it is open, and that the end of the
run brings the summary, with no console error.
Prints one line per check and "N passed, N failed"; exit status 1 on a
failure. Standard library only (pngcmp.py reads the screenshots).
"""
import base64
import json
import os
import select
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pngcmp  # noqa: E402

BROWSERS = ("chromium", "chromium-browser", "google-chrome")
TIMEOUT_S = 60.0


class Browser:
    """Chromium with the DevTools protocol on fds 3 (to it) and 4 (from it)."""

    def __init__(self, exe, profile):
        to_r, self.to_w = os.pipe()
        self.from_r, from_w = os.pipe()
        args = [exe, "--headless", "--no-sandbox", "--remote-debugging-pipe",
                "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                "--no-first-run", "--no-default-browser-check", "--disable-extensions",
                "--disable-background-networking", "--disable-dbus", "--hide-scrollbars",
                "--user-data-dir=" + profile, "--window-size=1000,620", "about:blank"]

        def fds():
            os.dup2(to_r, 3)
            os.dup2(from_w, 4)

        self.proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL, preexec_fn=fds, pass_fds=(3, 4),
                                     close_fds=True)
        os.close(to_r)
        os.close(from_w)
        self.buf = b""
        self.next_id = 0
        self.events = []
        self.session = None

    def send(self, method, params=None, session=True):
        self.next_id += 1
        msg = {"id": self.next_id, "method": method, "params": params or {}}
        if session and self.session:
            msg["sessionId"] = self.session
        os.write(self.to_w, json.dumps(msg).encode() + b"\0")
        want = self.next_id
        while True:
            m = self.receive(TIMEOUT_S)
            if m.get("id") == want:
                if "error" in m:
                    raise RuntimeError("%s: %s" % (method, m["error"].get("message")))
                return m.get("result", {})

    def receive(self, timeout):
        deadline = time.time() + timeout
        while b"\0" not in self.buf:
            left = deadline - time.time()
            if left <= 0 or not select.select([self.from_r], [], [], left)[0]:
                raise RuntimeError("no answer from the browser in %.0f s" % timeout)
            chunk = os.read(self.from_r, 1 << 20)
            if not chunk:
                raise RuntimeError("the browser closed its pipe")
            self.buf += chunk
        raw, self.buf = self.buf.split(b"\0", 1)
        m = json.loads(raw.decode())
        if "method" in m:
            self.events.append(m)
        return m

    def pump(self, seconds):
        end = time.time() + seconds
        while time.time() < end:
            try:
                self.receive(max(0.01, end - time.time()))
            except RuntimeError:
                return

    def evaluate(self, expr):
        r = self.send("Runtime.evaluate", {"expression": expr, "returnByValue": True,
                                           "awaitPromise": True})
        if "exceptionDetails" in r:
            raise RuntimeError("evaluate: " + r["exceptionDetails"].get("text", "exception"))
        return r["result"].get("value")

    def wait_title(self, prefix_ok, timeout=TIMEOUT_S):
        """Waits for the page's title to start with prefix_ok or "mission: error"."""
        end = time.time() + timeout
        title = ""
        while time.time() < end:
            title = self.evaluate("document.title") or ""
            if title.startswith(prefix_ok) or title.startswith("mission: error"):
                return title
            self.pump(0.1)
        return title

    def settle(self):
        """Lets the page handle what it was given and draw two frames."""
        self.evaluate("new Promise(function(r){setTimeout(function(){requestAnimationFrame("
                      "function(){requestAnimationFrame(function(){r(1);});});},50);})")

    def screenshot(self, clip, name):
        r = self.send("Page.captureScreenshot", {"format": "png", "clip": dict(clip, scale=1)})
        data = base64.b64decode(r["data"])
        keep = os.environ.get("VIEW_TEST_SHOTS")  # a folder to keep the screenshots in
        if keep:
            with open(os.path.join(keep, name + ".png"), "wb") as f:
                f.write(data)
        return pngcmp.read(data)

    def close(self):
        try:
            self.send("Browser.close", session=False)
        except (RuntimeError, OSError):
            pass
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()


def errors_in(events):
    """The console errors and uncaught exceptions among the protocol's events."""
    out = []
    for e in events:
        p = e.get("params", {})
        if e["method"] == "Runtime.exceptionThrown":
            d = p.get("exceptionDetails", {})
            out.append("exception: " + d.get("exception", {}).get("description", d.get("text", "")))
        elif e["method"] == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            out.append("console.error: " + " ".join(str(a.get("value", a.get("description", "")))
                                                     for a in p.get("args", [])))
        elif e["method"] == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            out.append("log: " + p["entry"].get("text", ""))
    return out


def frames_in(title):
    """The number of frames the page's title reports."""
    for part in title.split(","):
        part = part.strip()
        if part.endswith(" frames") and part.split()[0].isdigit():
            return int(part.split()[0])
    return -1


def live(b, url, check):
    """The checks of the live view on an open browser session."""
    start = time.time()
    b.send("Page.navigate", {"url": url})
    title = b.wait_title("mission: ok")
    n1 = frames_in(title)
    check(title.startswith("mission: ok") and "live" in title,
          "the live page loads (%.1f s, %d frames so far)" % (time.time() - start, n1),
          "title '%s'" % title)
    b.pump(1.5)
    b.settle()
    n2 = frames_in(b.evaluate("document.title") or "")
    check(n2 >= n1 + 5, "frames arrive while the page is open: %d, then %d after 1.5 s"
          % (n1, n2), "expected at least 5 more")
    title = b.wait_title("mission: ok, t = ", 1)
    end = time.time() + TIMEOUT_S
    while "the run has ended" not in title and time.time() < end:
        b.pump(0.2)
        title = b.evaluate("document.title") or ""
    text = b.evaluate("document.getElementById('summary').textContent") or ""
    check("the run has ended" in title and "real-time factor" in text,
          "the end of the run brings the summary (%d frames)" % frames_in(title),
          "title '%s', summary '%s'" % (title, text[:80]))


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--live":
        return run_checks(sys.argv[2], None, None)
    if len(sys.argv) not in (2, 4):
        sys.stderr.write("usage: view_browser.py PAGE.html [T_A T_B] | --live URL\n")
        return 2
    page = os.path.abspath(sys.argv[1])
    t_a, t_b = (float(sys.argv[2]), float(sys.argv[3])) if len(sys.argv) == 4 else (5.0, 28.0)
    return run_checks("file://" + page, t_a, t_b)


def run_checks(url, t_a, t_b):
    """The checks of a page (t_a, t_b given) or of the live view (None)."""
    passed = failed = 0

    def check(ok, what, why=""):
        nonlocal passed, failed
        if ok:
            passed += 1
            print("ok   " + what)
        else:
            failed += 1
            print("FAIL " + what + (": " + why if why else ""))
        return ok

    exe = next((b for b in BROWSERS if any(os.access(os.path.join(d, b), os.X_OK)
                                           for d in os.environ.get("PATH", "").split(":"))), None)
    if not check(exe is not None, "a Chromium to run",
                 "not installed (make test installs it: tools/ensure-deps.sh)"):
        print("%d passed, %d failed" % (passed, failed))
        return 1
    with tempfile.TemporaryDirectory() as profile:
        b = Browser(exe, profile)
        try:
            target = b.send("Target.createTarget", {"url": "about:blank"}, session=False)
            b.session = b.send("Target.attachToTarget", {"targetId": target["targetId"],
                                                         "flatten": True},
                               session=False)["sessionId"]
            for domain in ("Runtime", "Log", "Page"):
                b.send(domain + ".enable")
            if t_a is None:
                live(b, url, check)
                raise StopIteration
            start = time.time()
            b.send("Page.navigate", {"url": url + "#cam=overview&t=%g&vehicle=0" % t_a})
            title = b.wait_title("mission: ok")
            check(title.startswith("mission: ok"), "the page loads and draws its first frame "
                  "(%.1f s)" % (time.time() - start), "title '%s'" % title)
            rect = b.evaluate("(function(){var r=document.querySelector('#scene canvas')"
                              ".getBoundingClientRect();return {x:Math.round(r.left),"
                              "y:Math.round(r.top),width:Math.round(r.width),"
                              "height:Math.round(r.height)};})()") or {}
            if not check(rect.get("width", 0) > 100 and rect.get("height", 0) > 100,
                         "the 3-D view has a size (%sx%s)" % (rect.get("width"),
                                                               rect.get("height"))):
                raise RuntimeError("no 3-D view")
            box = (0, 0, rect["width"], rect["height"])
            b.settle()
            empty_a = b.screenshot(rect, "a_empty")
            b.evaluate("location.hash='cam=overview&t=%g&vehicle=1'" % t_a)
            b.wait_title("mission: ok, t = %.1f" % t_a)
            b.settle()
            shot_a = b.screenshot(rect, "a")
            mask_a = pngcmp.diff_mask(empty_a, shot_a, box)
            check(len(mask_a) >= 50, "the vehicle is drawn at t = %g s: %d pixels differ from "
                  "the empty scene" % (t_a, len(mask_a)), "expected at least 50")
            # The slider, as a user moves it: its value, then its input event.
            b.evaluate("(function(){var s=document.getElementById('slider');"
                       "s.value=String(Math.round(%g*10));"
                       "s.dispatchEvent(new Event('input'));})()" % t_b)
            title = b.wait_title("mission: ok, t = %.1f" % t_b)
            check(title.startswith("mission: ok, t = %.1f" % t_b),
                  "the slider moves the time to %g s" % t_b, "title '%s'" % title)
            b.settle()
            shot_b = b.screenshot(rect, "b")
            changed = set(pngcmp.diff_mask(shot_a, shot_b, box)) & set(mask_a)
            frac = len(changed) / float(len(mask_a) or 1)
            check(frac >= 0.5, "where the vehicle was at %g s, %.0f %% of its pixels changed at "
                  "%g s" % (t_a, 100 * frac, t_b), "expected at least 50 %")
            b.evaluate("location.hash='cam=overview&t=%g&vehicle=0'" % t_b)
            b.wait_title("mission: ok, t = %.1f" % t_b)
            b.settle()
            mask_b = pngcmp.diff_mask(b.screenshot(rect, "b_empty"), shot_b, box)
            (xa, ya), (xb, yb) = pngcmp.centroid(mask_a), pngcmp.centroid(mask_b)
            moved = ((xb - xa) ** 2 + (yb - ya) ** 2) ** 0.5
            check(len(mask_b) >= 50 and moved >= 10,
                  "the vehicle moved %.0f px on the screen (%d pixels at %g s)"
                  % (moved, len(mask_b), t_b), "expected at least 10 px")
        except StopIteration:
            pass
        except (RuntimeError, OSError, ValueError, KeyError) as e:
            check(False, "the browser session", str(e))
        finally:
            b.pump(0.2)
            errs = errors_in(b.events)
            check(not errs, "no console error or exception", "; ".join(errs)[:600])
            b.close()
    print("%d passed, %d failed" % (passed, failed))
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
