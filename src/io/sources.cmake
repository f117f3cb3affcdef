# sources of src/io
list(APPEND SC_SOURCES src/io/scene.c src/io/output.c src/io/plot.c
     src/io/plot_labels.c)
