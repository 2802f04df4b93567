# help2man fills the indented example lines of --help into one paragraph; keep them one
# command per line (no-fill from the section's first .IP to its end).
/^\.SH EXAMPLES$/,/^\.\(PP\|SH\)/{
  /^\.IP$/a\
.nf
  /^\.PP$/i\
.fi
  /^\.SH/{
    /EXAMPLES/!i\
.fi
  }
}
