# help2man fills the indented example lines of --help into one paragraph; keep them one
# command per line (no-fill from the section's first .IP to its end). A line indented
# deeper continues the command above it: help2man opens a paragraph for it, which would
# cut the command in two, so it stays in the block, indented under its command.
/^\.SH EXAMPLES$/,/^\.\(PP\|SH\)/{
  /^\.[IH]P$/{
    x
    /^nf$/{
      x
      N
      s/^\.[IH]P\n/    /
      b
    }
    s/.*/nf/
    x
    a\
.nf
  }
  /^\.PP$/i\
.fi
  /^\.SH/{
    /EXAMPLES/!i\
.fi
  }
}
