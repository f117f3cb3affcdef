# sources of src/models
