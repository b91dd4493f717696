"""Bad inputs: every one gives one located line and exit status 2."""
