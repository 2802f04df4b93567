"""`cmake --install` puts pvtap where Wireshark looks for extcaps: a relative link in the
extcap folder to the installed binary. Installed under a temporary DESTDIR, so nothing is left behind.
"""
import os
import shutil
import subprocess
import tempfile
import unittest

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120

PREFIX = "/usr/local"


class Install(unittest.TestCase):
    def setUp(self):
        self.build = os.environ["PVTAP_BUILD_DIR"]
        self.extcap_dir = os.environ["PVTAP_WIRESHARK_EXTCAP_DIR"]
        self.destdir = tempfile.mkdtemp(prefix="pvtap-install-")

    def tearDown(self):
        shutil.rmtree(self.destdir, ignore_errors=True)

    def test_extcap_folder_gets_a_link_to_the_installed_pvtap(self):
        subprocess.run(["cmake", "--install", self.build, "--prefix", PREFIX], check=True,
                       capture_output=True, env=dict(os.environ, DESTDIR=self.destdir),
                       timeout=RUN_GUARD_S)
        link = self.destdir + os.path.join(self.extcap_dir, "pvtap")
        self.assertTrue(os.path.islink(link), link + " is no link")
        # Relative, so that it resolves to the installed binary under DESTDIR too.
        self.assertFalse(os.path.isabs(os.readlink(link)), os.readlink(link))
        target = os.path.normpath(os.path.join(self.extcap_dir, os.readlink(link)))
        self.assertEqual(target, os.path.join(PREFIX, "bin", "pvtap"))
        binary = self.destdir + target
        self.assertTrue(os.access(binary, os.X_OK), binary)
        answer = subprocess.run([binary, "--extcap-interfaces"], capture_output=True, text=True,
                                check=True, timeout=RUN_GUARD_S)
        self.assertTrue(answer.stdout.startswith("extcap {version="), answer.stdout)


if __name__ == "__main__":
    unittest.main()
